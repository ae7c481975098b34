#include "export/write_export.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <tuple>

#include "core/error.h"
#include "core/model_choice.h"
#include "core/provenance.h"
#include "core/suggest.h"
#include "export/blender_script.h"
#include "export/gltf.h"
#include "export/lobe_material.h"
#include "export/provenance.h"
#include "export/scene_text.h"
#include "export/threejs_module.h"
#include "io/atomic_file.h"

namespace brdfit::exports {

namespace fs = std::filesystem;

namespace {

// Each format's --format name and main output's extension.
struct FormatSpelling {
  Format format;
  const char* name;
  const char* extension;
};
constexpr FormatSpelling kFormats[] = {
    {Format::kGltf, "gltf", ".gltf"},      {Format::kGlb, "glb", ".glb"},
    {Format::kMitsuba, "mitsuba", ".xml"}, {Format::kPbrt, "pbrt", ".pbrt"},
    {Format::kBlender, "blender", ".py"},  {Format::kThreejs, "threejs", ".mjs"},
};

const FormatSpelling& SpellingOf(Format format) {
  for (const FormatSpelling& f : kFormats) {
    if (f.format == format) return f;
  }
  throw std::logic_error("unknown export format");
}

}  // namespace

Format FormatFromString(const std::string& s) {
  for (const FormatSpelling& f : kFormats) {
    if (s == f.name) return f.format;
  }
  throw InputError("--format '" + s + "': expected gltf, glb, mitsuba, pbrt, blender or threejs");
}

const char* FormatName(Format format) {
  return SpellingOf(format).name;
}

const char* FormatExtension(Format format) {
  return SpellingOf(format).extension;
}

std::vector<std::string> MaterialsOf(const std::vector<FitReportEntry>& entries) {
  std::vector<std::string> materials;
  for (const auto& e : entries) {
    if (std::find(materials.begin(), materials.end(), e.material) == materials.end()) {
      materials.push_back(e.material);
    }
  }
  return materials;
}

std::vector<std::string> MaterialFileNames(const std::vector<std::string>& materials,
                                           Format format) {
  constexpr std::size_t kMaxStem = 96;
  auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  std::vector<std::string> names, taken;
  for (const std::string& m : materials) {
    std::string stem;
    for (const char c : m) {
      const bool ok =
          std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
      stem += ok && static_cast<unsigned char>(c) < 0x80 ? c : '_';
      if (stem.size() == kMaxStem) break;
    }
    if (!stem.empty() && (stem[0] == '.' || stem[0] == '-')) stem[0] = '_';
    if (stem.empty()) stem = "material";
    std::string name = stem;
    for (int k = 2; std::find(taken.begin(), taken.end(), lower(name)) != taken.end(); ++k) {
      name = stem + "-" + std::to_string(k);
    }
    taken.push_back(lower(name));
    names.push_back(name + FormatExtension(format));
  }
  return names;
}

namespace {

// Whether `a` ranks above `b`: a rendered score (the model choice's, dB) above none, a higher
// score first, then the lower log_rmse.
bool Better(const FitReportEntry& a, const FitReportEntry& b) {
  const RenderedError &ra = a.result.metrics.rendered, &rb = b.result.metrics.rendered;
  if (ra.ok != rb.ok) return ra.ok;
  if (ra.ok) {
    const double sa = RenderedScoreDb(ra), sb = RenderedScoreDb(rb);
    if (sa != sb) return sa > sb;
  }
  return a.result.metrics.log_rmse < b.result.metrics.log_rmse;
}

}  // namespace

Fidelity FidelityOf(const FitResult& fit, Format format) {
  if (format == Format::kThreejs) return {};
  if (!IsExportable(fit.model)) {
    return {{"the " + std::string(FormatName(format)) + " export takes only " +
             std::string(ExportableModels()) + ", not " + fit.model}};
  }
  const LobeMaterial m = FromFit(fit);
  switch (format) {
    case Format::kGltf:
    case Format::kGlb:
      return ToGltf(m).fidelity;
    case Format::kMitsuba:
      return ToMitsuba(m).fidelity;
    case Format::kPbrt:
      return ToPbrt(m).fidelity;
    case Format::kBlender:
      return ToBlender(m).fidelity;
    case Format::kThreejs:
      break;
  }
  return {};
}

const FitReportEntry& SelectEntry(const std::vector<FitReportEntry>& entries,
                                  const std::string& material, const std::string& model,
                                  Format format) {
  const std::vector<std::string> materials = MaterialsOf(entries);
  std::string list;
  for (const auto& m : materials) list += (list.empty() ? "" : ", ") + m;
  if (material.empty() && materials.size() > 1) {
    throw InputError("the fits hold several materials (" + list + "): choose one with --material");
  }
  std::vector<const FitReportEntry*> of;
  for (const auto& e : entries) {
    if (!material.empty() && e.material != material) continue;
    if (e.factorization && model == e.result.model) {
      throw InputError("a factorization exports from its sidecar: brdfit export " +
                       e.factorization->sidecar + " --format threejs");
    }
    // A factorization's textures are not a lobe material (io/fit_report.h): the analytic fits.
    if (!e.result.Failed() && !e.factorization) of.push_back(&e);
  }
  if (of.empty()) {
    throw InputError(material.empty()
                         ? std::string("no successful fit to export")
                         : "no successful fit of material '" + material + "'" +
                               SuggestionAfter(material, materials) + " (materials: " + list + ")");
  }
  std::string models;
  for (const auto* e : of) models += (models.empty() ? "" : ", ") + e->result.model;
  if (!model.empty()) {
    for (const auto* e : of) {
      if (e->result.model == model) return *e;
    }
    std::vector<std::string> fitted;
    for (const auto* e : of) fitted.push_back(e->result.model);
    throw InputError("no fit of model '" + model + "'" + SuggestionAfter(model, fitted) +
                     " (fitted: " + models + ")");
  }
  // Exact first; then the fewest lobes the format leaves out; then the chosen fit; then the
  // best. The other approximations (a masking form, a coloured ks, a layering) are not counted:
  // in three.js their number does not tell which export renders nearer the measurement, the
  // fit's own score does (docs/exports.md, "In a viewer"). three.js takes every model, exactly.
  const auto rank = [&](const FitReportEntry* e) {
    const Fidelity f = FidelityOf(e->result, format);
    return std::make_tuple(!f.Exact(), f.dropped_lobes, !e->chosen);
  };
  const FitReportEntry* nearest = nullptr;
  std::tuple<bool, int, bool> nearest_rank;
  for (const auto* e : of) {
    if (format != Format::kThreejs && !IsExportable(e->result.model)) continue;
    const auto r = rank(e);
    if (!nearest || r < nearest_rank || (r == nearest_rank && Better(*e, *nearest))) {
      nearest = e;
      nearest_rank = r;
    }
  }
  if (nearest) return *nearest;
  throw InputError("none of the fits (" + models + ") can be exported: fit one of " +
                   std::string(ExportableModels()) + " (brdfit fit TABLE --target " +
                   FormatName(format) + " fits the models this target expresses exactly)");
}

std::string SelectionNote(const std::vector<FitReportEntry>& entries,
                          const FitReportEntry& selected, Format format) {
  const FitReportEntry* chosen = nullptr;
  for (const auto& e : entries) {
    if (e.material == selected.material && e.chosen && !e.factorization && !e.result.Failed()) {
      chosen = &e;
    }
  }
  if (!chosen || chosen == &selected || chosen->result.model == selected.result.model) return {};
  const std::string why =
      !IsExportable(chosen->result.model) && format != Format::kThreejs
          ? "which " + std::string(FormatName(format)) + " cannot express"
          : "which " + std::string(FormatName(format)) + " expresses only approximately";
  const RenderedError &a = chosen->result.metrics.rendered, &b = selected.result.metrics.rendered;
  std::string gap;
  if (a.ok && b.ok) {
    gap = fmt::format("; {} scores {:.2f} dB, {:.2f} dB below the chosen fit's {:.2f} dB",
                      selected.result.model, RenderedScoreDb(b),
                      RenderedScoreDb(a) - RenderedScoreDb(b), RenderedScoreDb(a));
  }
  return fmt::format("brdfit chose {} for this material, {}: exporting {}{}", chosen->result.model,
                     why, selected.result.model, gap);
}

ExportOutcome WriteExport(const FitReportEntry& entry, const std::string& fits_path, Format format,
                          const fs::path& out, const std::string& brdf_glsl) {
  ExportOutcome o;
  if (format == Format::kThreejs) {
    if (brdf_glsl.empty()) throw std::logic_error("WriteExport(threejs) without the model's GLSL");
    const ThreejsAnalytic a{entry.result.model, entry.result.params, brdf_glsl};
    WriteTextAtomically(out,
                        ThreejsModule(a, ProvenanceOf(entry, fits_path, "three.js", o.fidelity)));
    o.written.push_back(out);
    return o;
  }
  const LobeMaterial m = FromFit(entry.result);
  switch (format) {
    case Format::kGltf:
    case Format::kGlb: {
      const GltfPbr g = ToGltf(m);
      o.fidelity = g.fidelity;
      const Provenance p = ProvenanceOf(entry, fits_path, "glTF 2.0", g.fidelity);
      if (format == Format::kGlb) {
        const GltfFiles f = BuildGltf(g, p, "");
        const std::vector<std::uint8_t> glb = PackGlb(f);
        WriteBytesAtomically(out, glb.data(), glb.size());
        o.written.push_back(out);
      } else {
        const fs::path bin = fs::path(out).replace_extension(".bin");
        if (bin == out) {
          throw OutputError(out, "a .gltf output named .bin would be its own buffer (-o x.gltf)");
        }
        const GltfFiles f = BuildGltf(g, p, bin.filename().string());
        WriteTwoFilesAtomically(out, f.json, bin, f.bin.data(), f.bin.size());
        o.written = {out, bin};
      }
      break;
    }
    case Format::kMitsuba: {
      const MitsubaBlend b = ToMitsuba(m);
      o.fidelity = b.fidelity;
      WriteTextAtomically(out,
                          MitsubaScene(b, ProvenanceOf(entry, fits_path, "Mitsuba 3", b.fidelity)));
      o.written.push_back(out);
      break;
    }
    case Format::kPbrt: {
      const PbrtMix x = ToPbrt(m);
      o.fidelity = x.fidelity;
      const std::string image = fs::path(out).filename().replace_extension(".exr").string();
      WriteTextAtomically(
          out, PbrtScene(x, ProvenanceOf(entry, fits_path, "pbrt-v4", x.fidelity), image));
      o.written.push_back(out);
      break;
    }
    case Format::kBlender: {
      const BlenderMaterial b = ToBlender(m);
      o.fidelity = b.fidelity;
      WriteTextAtomically(
          out, BlenderScript(b, ProvenanceOf(entry, fits_path, "Blender 3.4 Cycles", b.fidelity)));
      o.written.push_back(out);
      break;
    }
    case Format::kThreejs:
      break;  // written above
  }
  return o;
}

ExportOutcome WriteFactoredThreejs(const FactorFiles& files, const fs::path& json,
                                   const std::string& brdf_glsl, const fs::path& out) {
  ThreejsFactored f;
  f.parameterization = files.sidecar.at("parameterization").get<std::string>();
  f.diffuse = files.diffuse;
  for (const FactorTermFiles& t : files.terms) {
    f.p.push_back(t.p.image);
    f.q.push_back(t.q.image);
  }
  f.brdf_glsl = brdf_glsl;
  const nlohmann::json& sc = files.sidecar;
  Provenance p;
  p.version = std::string(BrdfitVersion());
  p.fits = json.string();
  std::string stem = json.filename().string();
  const std::string suffix = ".factor.json";
  if (stem.size() > suffix.size() && stem.ends_with(suffix))
    stem.resize(stem.size() - suffix.size());
  p.material = stem;
  const nlohmann::json src = sc.value("source", nlohmann::json::object());
  p.source = src.is_object() ? src.value("file", "?") : "?";
  p.source_hash = src.is_object() ? src.value("hash", "") : "";
  const bool diffuse = f.diffuse[0] > 0 || f.diffuse[1] > 0 || f.diffuse[2] > 0;
  p.model = fmt::format("factorization {}, rank {}{}", f.parameterization, f.p.size(),
                        diffuse ? " + diffuse" : "");
  p.target = "three.js";
  const nlohmann::json m = sc.value("metrics", nlohmann::json::object());
  const nlohmann::json r = m.is_object() ? m.value("rendered", nlohmann::json()) : nlohmann::json();
  if (r.is_object() && r.value("ok", false)) {
    p.metrics = fmt::format(
        "rendered error psnr {:.2f} dB, median relative {:.2f} %, p95 {:.2f} % (docs/accuracy.md)",
        r.value("psnr_db", 0.0), 100 * r.value("median_rel_error", 0.0),
        100 * r.value("p95_rel_error", 0.0));
  } else {
    p.metrics = "no rendered error in the sidecar";
  }
  ExportOutcome o;
  std::string text = ThreejsFactoredModule(f, p, &o.fidelity);
  if (!o.fidelity.Exact()) {  // the header states it: once more, now that the texels told
    p.fidelity = o.fidelity;
    Fidelity again;
    text = ThreejsFactoredModule(f, p, &again);
  }
  WriteTextAtomically(out, text);
  o.written.push_back(out);
  return o;
}

}  // namespace brdfit::exports
