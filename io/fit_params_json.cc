#include "io/fit_params_json.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdint>

#include <nlohmann/json.hpp>
#include <string>

#include "core/error.h"
#include "io/input_file.h"
#include "io/metrics_json.h"
#include "io/model_params.h"
#include "io/unique_keys_json.h"
#include "models/registry.h"

namespace brdfit {

namespace fs = std::filesystem;

namespace {

double Number(const fs::path& p, const nlohmann::json& j, const char* key,
              const std::string& where) {
  if (!j.contains(key)) return 0;
  if (!j[key].is_number()) throw InputError(p, where + "." + key + " is not a number");
  return j[key].get<double>();
}

// An error measure: a number >= 0 (0 when absent, as the writer leaves out what it lacks).
double NonNegative(const fs::path& p, const nlohmann::json& j, const char* key,
                   const std::string& where) {
  const double v = Number(p, j, key, where);
  if (!(v >= 0)) throw InputError(p, where + "." + key + " is negative");
  return v;
}

// A member the writer always makes of `type`, when present.
void CheckType(const fs::path& p, const nlohmann::json& j, const char* key,
               nlohmann::json::value_t type, const char* type_name, const std::string& where) {
  if (j.contains(key) && j[key].type() != type) {
    throw InputError(p, where + "." + key + " is not " + type_name);
  }
}

std::string String(const fs::path& p, const nlohmann::json& j, const char* key,
                   const std::string& where) {
  if (!j.contains(key)) return "";
  if (!j[key].is_string()) throw InputError(p, where + "." + key + " is not a string");
  return j[key].get<std::string>();
}

FitReportEntry Entry(const fs::path& p, const nlohmann::ordered_json& f, const std::string& where) {
  if (!f.is_object()) throw InputError(p, where + " is not an object");
  FitReportEntry e;
  const nlohmann::json fj = f;
  e.source = String(p, fj, "source", where);
  e.material = String(p, fj, "material", where);
  if (fj.contains("source_hash")) e.source_hash = String(p, fj, "source_hash", where);
  FitResult& r = e.result;
  r.model = String(p, fj, "model", where);
  r.message = String(p, fj, "message", where);
  const std::string status = String(p, fj, "status", where);
  r.status = status == "converged"        ? FitStatus::kConverged
             : status == "no_convergence" ? FitStatus::kNoConvergence
                                          : FitStatus::kFailed;
  if (f.contains("params")) {
    if (!f["params"].is_object()) throw InputError(p, where + ".params is not an object");
    for (const auto& [name, value] : f["params"].items()) {
      if (!value.is_number()) throw InputError(p, where + ".params." + name + " is not a number");
      r.param_names.push_back(name);
      r.params.push_back(value.get<double>());
    }
  }
  using T = nlohmann::json::value_t;
  CheckType(p, fj, "at_bound", T::array, "an array of parameter names", where);
  CheckType(p, fj, "metrics", T::object, "an object", where);
  CheckType(p, fj, "chosen", T::boolean, "true or false", where);
  CheckType(p, fj, "choice", T::string, "a string", where);
  CheckType(p, fj, "options", T::object, "an object", where);
  r.at_bound.assign(r.params.size(), false);
  if (fj.contains("at_bound")) {
    for (const auto& n : fj["at_bound"]) {
      if (!n.is_string()) throw InputError(p, where + ".at_bound holds a non-name");
      for (std::size_t i = 0; i < r.param_names.size(); ++i) {
        if (n.is_string() && n.get<std::string>() == r.param_names[i]) r.at_bound[i] = true;
      }
    }
  }
  if (r.model == kFactorizationModel) {
    // A factorization among the candidates (io/fit_report.h): no parameters, its sidecar.
    const std::string w = where + ".factorization";
    if (!r.params.empty()) throw InputError(p, where + ".params: a factorization has none");
    // A failed one (its solve, or its files) may have no textures to describe.
    if (!r.Failed() || fj.contains("factorization")) {
      if (!fj.contains("factorization") || !fj["factorization"].is_object()) {
        throw InputError(p, w + " is missing or not an object");
      }
      const nlohmann::json& fz = fj["factorization"];
      FactorizationRef ref;
      ref.form = String(p, fz, "form", w);
      ref.sidecar = String(p, fz, "sidecar", w);
      const double bytes = Number(p, fz, "texture_bytes", w), values = Number(p, fz, "values", w);
      if (ref.form.empty() || ref.sidecar.empty() || !(bytes >= 0 && bytes < 1e15) ||
          !(values >= 1 && values < 1e15)) {
        throw InputError(p, w + ": form, sidecar, texture_bytes >= 0 and values >= 1 are needed");
      }
      ref.texture_bytes = static_cast<std::uint64_t>(bytes);
      ref.values = static_cast<std::uint64_t>(values);
      e.factorization = ref;
    }
  } else if (!r.Failed()) {
    const ModelInfo* m = FindModel(r.model);
    if (!m) throw InputError(p, where + ".model '" + r.model + "' is not a registered model");
    std::string bad = CheckModelParamNames(*m, r.param_names);
    if (bad.empty()) bad = CheckModelParams(r.model, r.params);
    if (!bad.empty()) throw InputError(p, where + ".params are not the model's: " + bad);
  }
  if (fj.contains("metrics") && fj["metrics"].is_object()) {
    const nlohmann::json& m = fj["metrics"];
    const std::string w = where + ".metrics";
    r.metrics.ok = !r.Failed();
    r.metrics.log_rmse = NonNegative(p, m, "log_rmse", w);
    r.metrics.cbrt_rmse = NonNegative(p, m, "cbrt_rmse", w);
    r.metrics.rel_l2 = NonNegative(p, m, "rel_l2", w);
    r.metrics.weighting = String(p, m, "weighting", w);
    r.metrics.cutoff_deg = Number(p, m, "cutoff_deg", w);
    CheckType(p, m, "rendered", T::object, "an object", w);
    if (m.contains("rendered")) {
      const nlohmann::json& re = m["rendered"];
      RenderedError& out = r.metrics.rendered;
      CheckType(p, re, "ok", T::boolean, "true or false", w + ".rendered");
      out.ok = re.value("ok", false);
      out.problem = String(p, re, "problem", w + ".rendered");
      out.psnr_db = Number(p, re, "psnr_db", w + ".rendered");
      out.psnr_srgb_db = Number(p, re, "psnr_srgb_db", w + ".rendered");
      out.median_rel_error = NonNegative(p, re, "median_rel_error", w + ".rendered");
      out.p95_rel_error = NonNegative(p, re, "p95_rel_error", w + ".rendered");
      if (const std::string bad = RenderedLightsFromJson(re, &out); !bad.empty()) {
        throw InputError(p, w + ".rendered." + bad);
      }
    }
  }
  e.chosen = fj.value("chosen", false);
  e.choice =
      fj.contains("choice") && fj["choice"].is_string() ? fj["choice"].get<std::string>() : "";
  return e;
}

}  // namespace

std::vector<FitReportEntry> ReadFitParamsJson(const fs::path& path) {
  const std::vector<char> bytes = ReadWholeFile(path);
  // A key twice (nlohmann keeps the last) is refused; malformed text is reported below.
  try {
    (void)ParseJsonUniqueKeys(std::string(bytes.begin(), bytes.end()), path);
  } catch (const nlohmann::json::exception&) {
  }
  nlohmann::ordered_json j;
  try {
    j = nlohmann::ordered_json::parse(bytes.begin(), bytes.end());
  } catch (const nlohmann::json::exception& e) {
    // nlohmann's message names the byte and what it found (NaN, invalid UTF-8, 1e999, ...).
    throw InputError(path, std::string("not valid JSON: ") + PrintableExcerpt(e.what(), 200));
  }
  if (!j.is_object()) throw InputError(path, "not a JSON object");
  if (!j.contains("format") || j["format"] != "brdfit-fit-params") {
    throw InputError(path, "not brdfit fit parameters (\"format\" is not \"brdfit-fit-params\")");
  }
  if (!j.contains("format_version") || !j["format_version"].is_number_integer() ||
      j["format_version"].get<std::int64_t>() != kFitParamsJsonVersion) {
    throw InputError(path, fmt::format("format_version {} is not supported (this brdfit reads {})",
                                       j.contains("format_version") ? j["format_version"].dump()
                                                                    : std::string("(missing)"),
                                       kFitParamsJsonVersion));
  }
  if (!j.contains("fits") || !j["fits"].is_array()) {
    throw InputError(path, "\"fits\" is missing or not an array");
  }
  std::vector<FitReportEntry> out;
  for (std::size_t i = 0; i < j["fits"].size(); ++i) {
    const std::string where = fmt::format("fits[{}]", i);
    try {
      out.push_back(Entry(path, j["fits"][i], where));
    } catch (const nlohmann::json::exception& e) {
      // A member of another type than the reader expects: named with the file and the fit.
      throw InputError(path, where + ": a member of the wrong type (" + e.what() + ")");
    }
  }
  if (const auto two = TwoChosenOfOneMaterial(out)) {
    throw InputError(path, fmt::format("fits[{}] and fits[{}] are both chosen for material '{}' "
                                       "(a report chooses one fit per material)",
                                       two->first, two->second,
                                       PrintableExcerpt(out[two->second].material, 64)));
  }
  return out;
}

std::vector<FitReportEntry> ReadFitsAnyFormat(const fs::path& path) {
  CheckInputFile(path);
  const std::vector<char> head = ReadFilePrefix(path, 8);
  static const char kHdf5Signature[] = "\x89HDF\r\n\x1a\n";
  if (head.size() == 8 && std::equal(head.begin(), head.end(), kHdf5Signature)) {
    return ReadFitReport(path);
  }
  return ReadFitParamsJson(path);
}

}  // namespace brdfit
