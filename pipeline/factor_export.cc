#include "pipeline/factor_export.h"

#include <fmt/core.h>

#include "core/error.h"

namespace brdfit {
namespace {

constexpr const char* kAttrFormula = "brdfit:formula";
constexpr const char* kAttrArgument = "brdfit:argument";
constexpr const char* kAttrMap = "brdfit:map";
constexpr const char* kAttrMapFormula = "brdfit:map_formula";
constexpr const char* kAttrUnits = "brdfit:units";
constexpr const char* kAttrValues = "brdfit:values";
constexpr const char* kAttrGauge = "brdfit:gauge";
constexpr const char* kAttrSolver = "brdfit:solver";

static_assert(kFactorFileMaxRank == kMaxFactorRank, "the files hold every rank the solver makes");

const char* UnitsText(const char* units) {
  return std::string(units) == "1" ? "1 (dimensionless)" : units;
}

// Term k's product in the notation of the sidecar's texture names: "p2(wi) q2(wh) p2(wo)".
std::string TermFormula(const FactorParamSpec& spec, int k) {
  const std::string f = spec.formula;  // "f(wi,wo) = p(wi) q(wh) p(wo)"
  const std::string rhs = f.substr(f.find("= ") + 2);
  std::string out;
  for (std::size_t i = 0; i < rhs.size(); ++i) {
    const bool factor = (rhs[i] == 'p' || rhs[i] == 'q') && i + 1 < rhs.size() &&
                        rhs[i + 1] == '(' && (i == 0 || rhs[i - 1] == ' ');
    out += factor ? FactorTextureName(k, rhs[i] == 'q') : std::string(1, rhs[i]);
  }
  return out;
}

// The stored form: McCool et al.'s product at rank 1 without diffuse, else
// "f(wi,wo) = d + p(wi) q(wh) p(wo) + p2(wi) q2(wh) p2(wo)".
std::string Formula(const FactoredBrdf& b) {
  const FactorParamSpec& spec = b.spec();
  if (b.rank() == 1 && !b.has_diffuse()) return spec.formula;
  std::string s = "f(wi,wo) = ";
  if (b.has_diffuse()) s += "d + ";
  for (int k = 0; k < b.rank(); ++k) s += (k ? " + " : "") + TermFormula(spec, k);
  return s;
}

bool Refined(const FactorStats& s) {
  return s.refine_rows > 0;
}

std::string SolverText(const Factorization& r) {
  const FactorOptions& o = r.options;
  return fmt::format(
      "log-space least squares{}, resolution {}, lambda {}, weighting {}, max theta "
      "{} deg, rank {}, diffuse {}",
      Refined(r.stats) ? " + relative-loss refinement" : "", o.resolution, o.lambda,
      ToString(o.weighting), o.max_theta * 180 / kPi, r.brdf.rank(),
      r.brdf.has_diffuse() ? "yes" : "no");
}

ExrAttributes TextureAttributes(const Factorization& r, const FactorTextureSpec& t) {
  const FactorParamSpec& spec = r.brdf.spec();
  const bool sum = r.brdf.rank() > 1 || r.brdf.has_diffuse();
  return {
      {kAttrFormula, Formula(r.brdf)},
      {kAttrArgument, t.argument},
      {kAttrMap, ToString(t.map)},
      {kAttrMapFormula, MapFormula(t.map)},
      {kAttrUnits, UnitsText(t.units)},
      {kAttrValues,
       sum ? "linear factor values, float32, linear RGB; the diffuse value plus the sum of the "
             "products is f_r in 1/sr without the cosine"
           : "linear factor values, float32, linear RGB; the product is f_r in 1/sr without the "
             "cosine"},
      {kAttrGauge, spec.gauge},
      {kAttrSolver, SolverText(r)},
  };
}

nlohmann::json TextureJson(const FactorTextureSpec& t) {
  return {{"map", ToString(t.map)},
          {"map_formula", MapFormula(t.map)},
          {"argument", t.argument},
          {"units", t.units}};
}

}  // namespace

nlohmann::json DescribeFactorization(const Factorization& r) {
  const FactorParamSpec& spec = r.brdf.spec();
  const FactorStats& s = r.stats;
  const FactorOptions& o = r.options;
  nlohmann::json j;
  j["parameterization"] = ToString(spec.param);
  j["formula"] = Formula(r.brdf);
  j["values"] = "f_r in 1/sr without the cosine, linear RGB";
  j["diffuse_definition"] = "d = kd / pi in 1/sr, linear RGB, added to the sum of the products";
  j["gauge"] = spec.gauge;
  for (int k = 0; k < r.brdf.rank(); ++k) {
    j["textures"][FactorTextureName(k, false)] = TextureJson(spec.p);
    j["textures"][FactorTextureName(k, true)] = TextureJson(spec.q);
  }
  std::string method =
      "log-space linear least squares, sparse LDLT of the normal equations "
      "(docs/factorization.md)";
  if (Refined(s)) {
    method +=
        "; then Levenberg-Marquardt on the log-texel values (and the diffuse value) under the " +
        std::string(o.refine_loss == RefineLoss::kRel
                        ? "relative loss (f - m) / (|m| + eps)"
                        : "log-ratio loss ln((f + eps) / (m + eps))") +
        ", eps = 1e-3 1/sr, with solid-angle weights (factor/factor_refine.h)";
  }
  j["solver"] = {{"method", method},
                 {"resolution", o.resolution},
                 {"profile_knots", o.resolution},
                 {"lambda", o.lambda},
                 {"weighting", ToString(o.weighting)},
                 {"max_theta_deg", o.max_theta * 180 / kPi},
                 {"diffuse", o.diffuse},
                 {"rank", o.rank},
                 {"refine", o.refine},
                 {"refine_loss", ToString(o.refine_loss)},
                 {"refine_iterations", o.refine_iterations},
                 {"refine_rows", o.refine_rows}};
  j["stats"] = {{"grid_cells", s.grid_cells},
                {"valid_cells", s.valid_cells},
                {"usable_cells", s.usable_cells},
                {"nonpositive_cells_masked", s.nonpositive_cells},
                {"used_cells", s.used_cells},
                {"system_reused", s.system_reused},
                {"system_rebuilt_for_mask", s.system_rebuilt},
                {"pcg_iterations", s.pcg_iterations},
                {"clamped_texels", s.clamped_texels},
                {"system_seconds", s.system_seconds},
                {"seconds", s.seconds},
                {"solve_log_rms", s.solve_log_rms},
                {"refined", Refined(s)},
                {"refine_rows", s.refine_rows},
                {"refine_iterations", s.refine_iterations},
                {"refine_rel_rms_start", s.refine_rel_rms_start},
                {"refine_rel_rms", s.refine_rel_rms},
                {"refine_seconds", s.refine_seconds}};
  return j;
}

FactorPaths SaveFactorization(const Factorization& r, const std::filesystem::path& dir,
                              const std::string& stem, const nlohmann::json& extra,
                              bool include_timings) {
  const FactorParamSpec& spec = r.brdf.spec();
  FactorFiles files;
  files.sidecar = DescribeFactorization(r);
  if (!include_timings) {
    // What depends on the run, not on the table and the options: the times, and whether the
    // factored system came from an earlier table of the same process.
    for (const char* k : {"system_seconds", "seconds", "refine_seconds", "system_reused",
                          "system_rebuilt_for_mask"}) {
      files.sidecar["stats"].erase(k);
    }
  }
  files.sidecar.update(extra, /*merge_objects=*/true);
  files.diffuse = r.brdf.diffuse();
  // Provenance in every texture's header too (docs/formats.md): an EXR copied away from its
  // sidecar still says what made it.
  ExrAttributes provenance;
  if (extra.contains("provenance") && extra["provenance"].is_object()) {
    for (const auto& [key, value] : extra["provenance"].items()) {
      if (value.is_string()) provenance["brdfit:" + key] = value.get<std::string>();
    }
  }
  if (extra.contains("source") && extra["source"].is_object()) {
    const nlohmann::json& src = extra["source"];
    if (src.contains("file") && src["file"].is_string()) {
      provenance["brdfit:source"] = src["file"].get<std::string>();
    }
    if (src.contains("hash") && src["hash"].is_string()) {
      provenance["brdfit:source_hash"] = src["hash"].get<std::string>();
    }
  }
  auto attributes = [&](const FactorTextureSpec& t) {
    ExrAttributes a = TextureAttributes(r, t);
    a.insert(provenance.begin(), provenance.end());
    return a;
  };
  for (const FactorTerm& t : r.brdf.terms()) {
    files.terms.push_back({{t.p, attributes(spec.p)}, {t.q, attributes(spec.q)}});
  }
  const FactorPaths paths = FactorFilePaths(dir, stem, r.brdf.rank());
  WriteFactorFiles(paths, std::move(files));
  return paths;
}

FactoredBrdf LoadFactoredBrdf(const std::filesystem::path& json_path, nlohmann::json* sidecar) {
  FactorFiles f = ReadFactorFiles(json_path);
  FactorParam param;
  try {
    param = FactorParamFromString(f.sidecar["parameterization"].get<std::string>());
  } catch (const InputError& e) {
    throw InputError(json_path, e.what());
  }
  const FactorParamSpec& spec = GetFactorParamSpec(param);
  const std::filesystem::path dir = json_path.parent_path();
  std::vector<FactorTerm> terms;
  for (std::size_t k = 0; k < f.terms.size(); ++k) {
    for (const bool is_q : {false, true}) {
      const FactorTextureFile& tex = is_q ? f.terms[k].q : f.terms[k].p;
      const FactorMap want = is_q ? spec.q.map : spec.p.map;
      const auto it = tex.attributes.find(kAttrMap);
      const std::string map = it == tex.attributes.end() ? "(missing)" : it->second;
      if (map != ToString(want)) {
        const std::string name = FactorTextureName(static_cast<int>(k), is_q);
        throw InputError(dir / f.sidecar["textures"][name]["file"].get<std::string>(),
                         fmt::format("attribute {} is '{}', parameterization {} needs '{}'",
                                     kAttrMap, map, ToString(param), ToString(want)));
      }
    }
    terms.push_back({std::move(f.terms[k].p.image), std::move(f.terms[k].q.image)});
  }
  if (sidecar) *sidecar = f.sidecar;
  try {
    return FactoredBrdf(param, f.diffuse, std::move(terms));
  } catch (const InputError& e) {
    throw InputError(json_path, e.what());
  }
}

}  // namespace brdfit
