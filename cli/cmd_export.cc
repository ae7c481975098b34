// `brdfit export FITS --format gltf|glb|mitsuba|pbrt|blender|threejs|bsdf [--material NAME]
// [--model NAME] -o OUT|DIR/`: one fit of a fit report or JSON parameters (or a factorization,
// threejs and bsdf; or a table, bsdf), or with a folder one per material, as a glTF 2.0 asset,
// a Mitsuba 3 scene, a pbrt-v4 scene, a Blender Python script, a three.js module or an RGL
// .bsdf (export/, pipeline/bsdf_export.h, docs/exports.md). What the target cannot express
// exactly is said in the file and on stderr.
#include <fmt/core.h>

#include <filesystem>
#include <string>

#include "cli/command.h"
#include "cli/terminal_text.h"
#include "core/error.h"
#include "core/provenance.h"
#include "export/fit_targets.h"
#include "export/scene_text.h"
#include "export/write_export.h"
#include "io/atomic_file.h"
#include "io/factor_io.h"
#include "io/fit_params_json.h"
#include "io/output_policy.h"
#include "pipeline/bsdf_export.h"
#include "pipeline/inputs.h"
#include "pipeline/refit_source.h"
#include "preview/shader_gen.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

struct ExportOptions {
  std::string fits, format, material, model, out;
  bool quiet = false;
  bool no_fit = false;  // never fit the target's models on the spot
  RglBuildOptions bsdf;    // --format bsdf resolutions
  std::string bsdf_scene;  // --bsdf-scene: "", "pbrt" or "mitsuba"
};

bool IsFactorSidecar(const std::string& path) {
  const std::string suffix = ".factor.json";
  return path.size() >= suffix.size() && path.ends_with(suffix);
}

// A factorization's sidecar: only the three.js module can carry its textures.
int RunFactorExport(const ExportOptions& o, exports::Format format) {
  if (format != exports::Format::kThreejs) {
    throw InputError(o.fits +
                     ": a factorization exports only as --format threejs (the other "
                     "targets take a fit report or fit JSON)");
  }
  CheckOutputs({o.fits}, {{o.out, "-o"}});
  const FactorFiles files = ReadFactorFiles(o.fits);
  const std::string glsl =
      preview::FactoredBrdfSource(files.sidecar.at("parameterization").get<std::string>(),
                                  static_cast<int>(files.terms.size()));
  const exports::ExportOutcome r = exports::WriteFactoredThreejs(files, o.fits, glsl, o.out);
  for (const std::string& a : r.fidelity.approximations) {
    fmt::print(stderr, "brdfit: export: approximate: {}\n", a);
  }
  if (!o.quiet) fmt::print("{} -> {}\n", TerminalSafe(o.fits), TerminalSafe(o.out));
  return kExitOk;
}

// The files an export to `out` writes: it, and for glTF its .bin beside it.
void AddPlannedOutputs(const fs::path& out, exports::Format format,
                       std::vector<PlannedOutput>* outs) {
  outs->push_back({out, "-o"});
  if (format == exports::Format::kGltf) {
    outs->push_back({fs::path(out).replace_extension(".bin"), "-o (its .bin)"});
  }
}

// exports::SelectEntry, its error naming the fits file (which fits hold no such entry).
const FitReportEntry& Select(const std::vector<FitReportEntry>& entries,
                             const std::string& material, const ExportOptions& o,
                             exports::Format format) {
  try {
    return exports::SelectEntry(entries, material, o.model, format);
  } catch (const InputError& err) {
    if (!err.path().empty()) throw;
    throw InputError(o.fits, err.what());
  }
}

// Whether the fits of `material` include one of the target's own models.
bool HasTargetFit(const std::vector<FitReportEntry>& entries, const std::string& material,
                  const exports::FitTarget& target) {
  for (const FitReportEntry& e : entries) {
    if (e.material != material || e.result.Failed() || e.factorization) continue;
    for (const std::string& m : target.models) {
      if (e.result.model == m) return true;
    }
  }
  return false;
}

// Without --model, a material whose fits include none of the target's own models (the ones
// `brdfit fit --target` fits, export/fit_targets.h) gets them fitted on the spot to the table
// its fits came from, added to `entries` for the selection (exports::SelectEntry); the fits
// file is not modified. When the table cannot be read (moved, changed), the export goes on
// with the fits there are and says why.
void FitTargetModelsOnTheSpot(std::vector<FitReportEntry>* entries, const std::string& material,
                              const ExportOptions& o, exports::Format format) {
  const exports::FitTarget* target = exports::FitTargetForFormat(format);
  if (o.no_fit || !o.model.empty() || !target || HasTargetFit(*entries, material, *target)) {
    return;
  }
  const FitReportEntry* of = nullptr;
  for (const FitReportEntry& e : *entries) {
    if (e.material == material && !e.result.Failed() && !e.factorization && (!of || e.chosen)) {
      of = &e;
    }
  }
  if (!of) return;
  std::string models;
  for (const std::string& m : target->models) models += (models.empty() ? "" : ", ") + m;
  pipeline::SourceRefit refit;
  try {
    refit = pipeline::RefitSource(*of, target->models);
  } catch (const std::exception& err) {  // InputError, or a scratch report not writable
    fmt::print(stderr,
               "brdfit: export: note: {}: the fits hold none of {}'s own models, and {} could "
               "not be fitted on the spot ({}): exporting the nearest\n",
               TerminalSafe(material), exports::FormatName(format), models,
               TerminalSafe(err.what()));
    return;
  }
  fmt::print(stderr,
             "brdfit: export: note: {}: {} holds none of {}'s own models: fitted {} to {} on "
             "the spot{} (not saved; brdfit fit {} --target {} keeps them)\n",
             TerminalSafe(material), TerminalSafe(o.fits), exports::FormatName(format), models,
             TerminalSafe(of->source),
             refit.same_options ? "" : " with brdfit fit's default options, not the report's",
             TerminalSafe(of->source), target->name);
  for (FitReportEntry& e : refit.entries) entries->push_back(std::move(e));
}

// -o names a folder: one that exists, or a name ending in '/'.
bool NamesFolder(const std::string& out) {
  return out.ends_with('/') || fs::is_directory(out);
}

// The chosen fit's note when a factorization was chosen and the analytic fit `e` is exported,
// or when the chosen analytic fit is not what the format takes exactly.
void NoteChoice(const std::vector<FitReportEntry>& entries, const FitReportEntry& e,
                const ExportOptions& o, exports::Format format) {
  if (o.model.empty()) {
    const std::string note = exports::SelectionNote(entries, e, format);
    if (!note.empty()) {
      fmt::print(stderr, "brdfit: export: note: {}: {}\n", TerminalSafe(e.material),
                 TerminalSafe(note));
    }
  }
  for (const FitReportEntry& c : entries) {
    if (c.chosen && c.factorization && c.material == e.material && o.model.empty()) {
      fmt::print(stderr,
                 "brdfit: export: note: the approximation chosen for {} is a factorization ({}); "
                 "this exports the analytic fit {} (the factorization: brdfit export {} "
                 "--format threejs)\n",
                 TerminalSafe(c.material), c.factorization->form, e.result.model,
                 TerminalSafe(c.factorization->sidecar));
    }
  }
}

// Writes one entry and prints what was written.
void WriteOne(const FitReportEntry& e, const ExportOptions& o, exports::Format format,
              const fs::path& out) {
  const std::string glsl =
      format == exports::Format::kThreejs ? preview::AnalyticBrdfSource(e.result.model) : "";
  const exports::ExportOutcome r = exports::WriteExport(e, o.fits, format, out, glsl);
  for (const std::string& a : r.fidelity.approximations) {
    fmt::print(stderr, "brdfit: export: approximate: {}: {}\n", TerminalSafe(e.material), a);
  }
  if (!o.quiet) {
    std::string files;
    for (const auto& p : r.written) files += (files.empty() ? "" : ", ") + p.string();
    fmt::print("{} {} ({}) -> {} [{}]\n", TerminalSafe(e.material), e.result.model,
               TerminalSafe(e.source), TerminalSafe(files),
               r.fidelity.Exact() ? "exact" : "approximate");
  }
}

// -o DIR: every material of the fits (or --material's), one file each named by
// exports::MaterialFileNames. Every selection is made before anything is written: a material
// with nothing to export stops the command with nothing written.
int RunExportFolder(const ExportOptions& o, exports::Format format) {
  if (IsFactorSidecar(o.fits)) {
    throw InputError(o.fits + ": a factorization exports as one file: give -o NAME.mjs");
  }
  const fs::path dir = o.out;
  CheckOutputFolder(dir, "-o");
  std::vector<FitReportEntry> entries = ReadFitsAnyFormat(o.fits);
  std::vector<std::string> materials = exports::MaterialsOf(entries);
  if (!o.material.empty()) materials = {o.material};
  for (const std::string& m : materials) FitTargetModelsOnTheSpot(&entries, m, o, format);
  std::vector<const FitReportEntry*> chosen;
  for (const std::string& m : materials) chosen.push_back(&Select(entries, m, o, format));
  const std::vector<std::string> names = exports::MaterialFileNames(materials, format);
  std::vector<PlannedOutput> outs;
  for (const std::string& n : names) AddPlannedOutputs(dir / n, format, &outs);
  MakeOutputFolder(dir);
  CheckOutputs({o.fits}, outs);
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    NoteChoice(entries, *chosen[i], o, format);
    WriteOne(*chosen[i], o, format, dir / names[i]);
  }
  return kExitOk;
}

// --format bsdf: every analytic model evaluates exactly, so the fit exported is --model's, else
// the chosen one, else the best (exports::SelectEntry's rule for three.js, which also evaluates
// every model).
int RunBsdfExport(const ExportOptions& o) {
  if (NamesFolder(o.out)) {
    throw InputError(o.out +
                     ": --format bsdf writes one file (-o NAME.bsdf); --material picks the "
                     "material of a report that holds several");
  }
  RglBuildOptions build = o.bsdf;
  const std::string bsdf_name = fs::path(o.out).filename().string();
  fs::path scene;
  if (!o.bsdf_scene.empty()) {
    // pbrt-v4's measured material reads spectral files only; Mitsuba's reads them in its
    // spectral variants: a scene gets a spectral file.
    build.spectral = true;
    scene = fs::path(o.out).replace_extension(o.bsdf_scene == "pbrt" ? ".pbrt" : ".xml");
    if (!exports::PbrtStringHolds(bsdf_name)) {
      throw InputError(o.out +
                       ": a scene cannot name this file (quotes, backslashes and "
                       "characters outside printable ASCII cannot be written in a pbrt "
                       "string): choose another -o name");
    }
  }
  std::vector<PlannedOutput> outs = {{o.out, "-o"}};
  if (!scene.empty()) outs.push_back({scene.string(), "--bsdf-scene"});
  CheckOutputs({o.fits}, outs);
  pipeline::BsdfExport r;
  if (IsFactorSidecar(o.fits)) {
    r = pipeline::ExportFactorAsBsdf(o.fits, build, o.out);
  } else if (const auto fits = pipeline::BsdfInputFits(o.fits)) {
    const FitReportEntry& e =
        exports::SelectEntry(*fits, o.material, o.model, exports::Format::kThreejs);
    r = pipeline::ExportFitAsBsdf(e, build, o.out);
  } else {
    r = pipeline::ExportTableAsBsdf(pipeline::LoadInput(o.fits), o.fits, build, o.out);
  }
  if (!scene.empty()) {
    const std::vector<std::string> header = {
        "brdfit " + std::string(BrdfitVersion()) + " export, format bsdf, scene " + o.bsdf_scene,
        "source: " + r.source, "material: " + bsdf_name};
    WriteTextAtomically(
        scene,
        o.bsdf_scene == "pbrt"
            ? exports::PbrtMeasuredScene(
                  bsdf_name, header, fs::path(o.out).filename().replace_extension(".exr").string())
            : exports::MitsubaMeasuredScene(bsdf_name, header));
  }
  if (r.build.unmeasured) {
    fmt::print(stderr,
               "brdfit: export: {} warped samples have no value in the source (masked cells): "
               "marked unmeasured in the file's 'valid' field\n",
               r.build.unmeasured);
  }
  if (r.build.spectral_clamped) {
    fmt::print(stderr,
               "brdfit: export: {} spectral values below 0 (saturated colours) written as 0\n",
               r.build.spectral_clamped);
  }
  if (r.build.negative) {
    fmt::print(stderr, "brdfit: export: {} samples had a channel below 0, written as 0\n",
               r.build.negative);
  }
  if (!o.quiet) {
    fmt::print(
        "{} -> {} (RGL .bsdf, {}: {} incident elevations to {} deg, {}x{} warped samples "
        "each, NDF of {} samples from {} power iterations)\n",
        TerminalSafe(r.source), TerminalSafe(o.out), build.spectral ? "spectral 360-830 nm" : "RGB",
        o.bsdf.theta_i_count, o.bsdf.theta_i_max_deg, o.bsdf.warp_samples, o.bsdf.warp_samples,
        o.bsdf.ndf_samples, r.build.power_iterations);
  }
  if (!o.quiet && !scene.empty()) fmt::print("scene {}\n", TerminalSafe(scene.string()));
  return kExitOk;
}

int RunExport(const ExportOptions& o) {
  if (o.format == "bsdf") return RunBsdfExport(o);
  const exports::Format format = exports::FormatFromString(o.format);
  if (o.out == "-") {
    throw InputError(
        "-o -: export writes files (a .gltf has its .bin beside it); give a file "
        "name");
  }
  if (NamesFolder(o.out)) return RunExportFolder(o, format);
  if (IsFactorSidecar(o.fits)) return RunFactorExport(o, format);
  std::vector<PlannedOutput> outs;
  AddPlannedOutputs(o.out, format, &outs);
  CheckOutputs({o.fits}, outs);
  std::vector<FitReportEntry> entries = ReadFitsAnyFormat(o.fits);
  const std::vector<std::string> materials = exports::MaterialsOf(entries);
  if (materials.size() == 1 || !o.material.empty()) {
    FitTargetModelsOnTheSpot(&entries, o.material.empty() ? materials[0] : o.material, o, format);
  }
  const FitReportEntry& e = Select(entries, o.material, o, format);
  NoteChoice(entries, e, o, format);
  WriteOne(e, o, format, o.out);
  return kExitOk;
}

Registrar reg{
    "export",
    "Write a fitted material for glTF 2.0, Mitsuba 3, pbrt-v4, Blender (a sphere scene with it) or "
    "three.js, or a fit, factorization or table as an RGL .bsdf",
    [](CLI::App& sub) {
      auto o = std::make_shared<ExportOptions>();
      sub.add_option("fits", o->fits,
                     "fit report (.h5), JSON parameters of brdfit fit, or (threejs, bsdf) a "
                     "factorization's .factor.json, or (bsdf) a table: .binary, .h5, .bsdf, "
                     "nbrdf:NAME")
          ->required();
      sub.add_option(
             "--format", o->format,
             "gltf (.gltf + .bin) | glb | mitsuba | pbrt | blender (a .py) | threejs (a .mjs) | "
             "bsdf (RGL measured format: pbrt-v4 and Mitsuba 'measured')")
          ->required();
      sub.add_option("--bsdf-warp", o->bsdf.warp_samples,
                     "bsdf: warped samples per side and incident elevation")
          ->check(CLI::Range(4, 1024))
          ->capture_default_str();
      sub.add_option("--bsdf-theta-i", o->bsdf.theta_i_count,
                     "bsdf: incident elevations, uniform from 0 to 88 deg")
          ->check(CLI::Range(2, 1024))
          ->capture_default_str();
      sub.add_flag("--bsdf-spectral", o->bsdf.spectral,
                   "bsdf: spectral values (360-830 nm), which pbrt-v4's 'measured' material "
                   "needs; default RGB");
      sub.add_option("--bsdf-scene", o->bsdf_scene,
                     "bsdf: also write OUT's pbrt-v4 (.pbrt) or Mitsuba 3 (.xml) sphere scene "
                     "with the measured material reading it (implies --bsdf-spectral)")
          ->check(CLI::IsMember({"pbrt", "mitsuba"}));
      sub.add_option("--bsdf-spread", o->bsdf.ndf_spread,
                     "bsdf: weight of the cosine NDF mixed into the stored one, so that warped "
                     "samples also cover the hemisphere away from a sharp peak")
          ->check(CLI::Range(0.0, 0.99))
          ->capture_default_str();
      sub.add_option("--bsdf-ndf", o->bsdf.ndf_samples, "bsdf: NDF and projected-area samples")
          ->check(CLI::Range(8, 4096))
          ->capture_default_str();
      sub.add_option("--material", o->material, "material to export (when the fits hold several)");
      sub.add_option("--model", o->model,
                     "fit to export (default: the chosen fit when the format expresses it "
                     "exactly, else the best-scored fit it does, else the best exportable; a "
                     "note says how far it is from the chosen fit; threejs: any model, the "
                     "chosen fit)");
      sub.add_option("-o,--out", o->out,
                     "output file; or a folder (one that exists, or a name ending in '/'): "
                     "every material of the fits (or --material's), one file each, named "
                     "after the material")
          ->required();
      sub.add_flag("--no-fit", o->no_fit,
                   "never fit on the spot (default: when a material's fits hold none of the "
                   "target's own models, fit them to the table the fits came from, as brdfit "
                   "fit --target does, without saving them, and export the best)");
      sub.add_flag("-q,--quiet", o->quiet, "no summary line");
      sub.footer(
          "Exit codes: 0 ok, 2 bad input or output. Exportable models: lambert+ggx-hc, "
          "lambert+ggx, lambert+ggx-f0, ue4, lambert+ggx+sheen, lambert+ggx+ggx, "
          "oren-nayar-fujii+ggx, burley-2012+ggx (threejs: any analytic model); "
          "docs/exports.md has the "
          "mappings.\n"
          "Examples:\n  brdfit fit gold.binary --model ggx-hc --json fits.json\n"
          "  brdfit export fits.json --format glb -o gold.glb\n"
          "  brdfit export fits.h5 --format pbrt -o scenes/\n"
          "  brdfit export gold.binary --format bsdf -o gold.bsdf");
      return [o] { return RunExport(*o); };
    }};

}  // namespace
}  // namespace brdfit::cli
