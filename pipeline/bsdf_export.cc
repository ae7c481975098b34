#include "pipeline/bsdf_export.h"

#include <cmath>
#include <stdexcept>

#include "core/error.h"
#include "core/input_name.h"
#include "core/provenance.h"
#include "fit/rendered_error.h"
#include "io/fit_params_json.h"
#include "io/rgl_bsdf_file.h"
#include "io/table_io.h"
#include "models/registry.h"
#include "pipeline/factor_export.h"

namespace brdfit::pipeline {

namespace fs = std::filesystem;

namespace {

using Rgb = std::array<double, 3>;

BsdfExport Write(const std::function<bool(const Vec3&, const Vec3&, Rgb*)>& eval,
                 const std::string& source, RglBuildOptions options, const fs::path& out) {
  options.description = "brdfit " + std::string(BrdfitVersion()) + ": " + source;
  const BrdfSource f = [&eval](const Vec3& wi, const Vec3& wo, double rgb[3]) {
    Rgb v{};
    if (!eval(wi, wo, &v)) return false;
    for (int c = 0; c < 3; ++c) rgb[c] = v[static_cast<std::size_t>(c)];
    return true;
  };
  BsdfExport r;
  r.source = source;
  try {
    const RglBsdf b = BuildRglBsdf(f, options, &r.build);
    WriteRglBsdf(b, out);
  } catch (const std::invalid_argument& e) {
    throw InputError(out, e.what());
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const InputError*>(&e) || dynamic_cast<const OutputError*>(&e)) throw;
    throw InputError(source + ": " + e.what());
  }
  return r;
}

}  // namespace

std::optional<std::vector<FitReportEntry>> BsdfInputFits(const std::string& input) {
  if (IsNbrdfInput(input)) return std::nullopt;
  if (!input.ends_with(".json") && DetectTableFormat(input) != TableFormat::kHdf5) {
    return std::nullopt;
  }
  try {
    return ReadFitsAnyFormat(input);
  } catch (const InputError& e) {
    if (input.ends_with(".json") ||
        std::string(e.what()).find(kFitReportFormat) == std::string::npos) {
      throw;
    }
    return std::nullopt;  // an HDF5 file of another format: a table (LoadTable says if not)
  }
}

BsdfExport ExportFitAsBsdf(const FitReportEntry& entry, RglBuildOptions options,
                           const fs::path& out) {
  const ModelInfo* model = FindModel(entry.result.model);
  if (!model || entry.result.params.size() != model->param_names.size()) {
    throw InputError("the fit " + entry.result.model + " of " + entry.material +
                     " cannot be evaluated (unknown model or wrong parameter count)");
  }
  const BrdfFunction f = ModelBrdf(*model, entry.result.params);
  return Write(
      [&f](const Vec3& wi, const Vec3& wo, Rgb* v) {
        *v = f(wi, wo);
        return true;
      },
      entry.result.model + " fit of " + entry.material, options, out);
}

BsdfExport ExportFactorAsBsdf(const fs::path& sidecar, RglBuildOptions options,
                              const fs::path& out) {
  const FactoredBrdf f = LoadFactoredBrdf(sidecar);
  return Write(
      [&f](const Vec3& wi, const Vec3& wo, Rgb* v) {
        *v = f.Eval(wi, wo);
        return true;
      },
      "factorization " + sidecar.filename().string(), options, out);
}

BsdfExport ExportTableAsBsdf(const Table& table, const std::string& name, RglBuildOptions options,
                             const fs::path& out) {
  return Write(
      [&table](const Vec3& wi, const Vec3& wo, Rgb* v) {
        const auto x = table.LookupTrilinear(wi, wo);
        if (!x) return false;
        *v = *x;
        return true;
      },
      "table " + name, options, out);
}

}  // namespace brdfit::pipeline
