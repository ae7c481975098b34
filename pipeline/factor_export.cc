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

const char* UnitsText(const char* units) {
  return std::string(units) == "1" ? "1 (dimensionless)" : units;
}

ExrAttributes TextureAttributes(const Factorization& r, const FactorTextureSpec& t) {
  const FactorParamSpec& spec = r.brdf.spec();
  return {
      {kAttrFormula, spec.formula},
      {kAttrArgument, t.argument},
      {kAttrMap, ToString(t.map)},
      {kAttrMapFormula, MapFormula(t.map)},
      {kAttrUnits, UnitsText(t.units)},
      {kAttrValues,
       "linear factor values, float32, linear RGB; the product is f_r in 1/sr without the "
       "cosine"},
      {kAttrGauge, spec.gauge},
      {kAttrSolver, fmt::format("log-space least squares, resolution {}, lambda {}, "
                                "weighting {}, max theta {} deg",
                                r.options.resolution, r.options.lambda,
                                ToString(r.options.weighting), r.options.max_theta * 180 / kPi)},
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
  nlohmann::json j;
  j["parameterization"] = ToString(spec.param);
  j["formula"] = spec.formula;
  j["values"] = "f_r in 1/sr without the cosine, linear RGB";
  j["gauge"] = spec.gauge;
  j["textures"]["p"] = TextureJson(spec.p);
  j["textures"]["q"] = TextureJson(spec.q);
  j["solver"] = {{"method",
                  "log-space linear least squares, sparse LDLT of the normal "
                  "equations (docs/factorization.md)"},
                 {"resolution", r.options.resolution},
                 {"profile_knots", r.options.resolution},
                 {"lambda", r.options.lambda},
                 {"weighting", ToString(r.options.weighting)},
                 {"max_theta_deg", r.options.max_theta * 180 / kPi}};
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
                {"solve_log_rms", s.solve_log_rms}};
  return j;
}

FactorPaths SaveFactorization(const Factorization& r, const std::filesystem::path& dir,
                              const std::string& stem, const nlohmann::json& extra) {
  const FactorParamSpec& spec = r.brdf.spec();
  FactorFiles files;
  files.sidecar = DescribeFactorization(r);
  files.sidecar.update(extra, /*merge_objects=*/true);
  files.p = {r.brdf.p(), TextureAttributes(r, spec.p)};
  files.q = {r.brdf.q(), TextureAttributes(r, spec.q)};
  const FactorPaths paths = FactorFilePaths(dir, stem);
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
  const FactorTextureSpec* specs[2] = {&spec.p, &spec.q};
  const FactorTextureFile* tex[2] = {&f.p, &f.q};
  const char* names[2] = {"p", "q"};
  for (int k = 0; k < 2; ++k) {
    const auto it = tex[k]->attributes.find(kAttrMap);
    const std::string map = it == tex[k]->attributes.end() ? "(missing)" : it->second;
    if (map != ToString(specs[k]->map)) {
      throw InputError(dir / f.sidecar["textures"][names[k]]["file"].get<std::string>(),
                       fmt::format("attribute {} is '{}', parameterization {} needs '{}'", kAttrMap,
                                   map, ToString(param), ToString(specs[k]->map)));
    }
  }
  if (sidecar) *sidecar = f.sidecar;
  try {
    return FactoredBrdf(param, std::move(f.p.image), std::move(f.q.image));
  } catch (const InputError& e) {
    throw InputError(json_path, e.what());
  }
}

}  // namespace brdfit
