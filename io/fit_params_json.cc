#include "io/fit_params_json.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdint>

#include <nlohmann/json.hpp>
#include <string>

#include "core/error.h"
#include "core/model_params.h"
#include "io/input_file.h"
#include "io/metrics_json.h"
#include "io/result_json.h"
#include "io/unique_keys_json.h"
#include "models/registry.h"

namespace brdfit {

namespace fs = std::filesystem;

namespace {

// One fit of "fits" with the strictness of every result reader (io/result_json.h): a member
// that is present has its type and range; a usable fit has its registered model's parameters,
// in order and in bounds, and its metrics.
FitReportEntry Entry(const fs::path& p, const nlohmann::ordered_json& f, const std::string& where) {
  if (!f.is_object()) throw InputError(p, where + " is not an object");
  const JsonFields ff(p, where);
  const nlohmann::json fj = f;  // unordered for the members whose order does not matter
  FitReportEntry e;
  e.source = ff.String(fj, "source", "");
  e.material = ff.String(fj, "material", "");
  e.source_hash = ff.String(fj, "source_hash", "");
  FitResult& r = e.result;
  r.model = ff.String(fj, "model", "");
  r.message = ff.String(fj, "message", "");
  const std::string status = ff.String(fj, "status", "");
  const std::optional<FitStatus> known = kFitStatusNames.Find(status);
  if (!known)
    ff.Fail("status", "is '" + PrintableExcerpt(status, 64) + "', not " + kFitStatusNames.List());
  r.status = *known;
  // Ordered: the parameters keep the model's order.
  if (f.contains("params")) {
    if (!f["params"].is_object()) ff.Fail("params", "is not an object");
    for (const auto& [name, value] : f["params"].items()) {
      if (!value.is_number()) ff.Fail("params." + name, "is not a number");
      r.param_names.push_back(name);
      r.params.push_back(value.get<double>());
    }
  }
  r.at_bound.assign(r.params.size(), false);
  if (fj.contains("at_bound")) {
    if (!fj["at_bound"].is_array()) ff.Fail("at_bound", "is not an array of parameter names");
    for (const auto& n : fj["at_bound"]) {
      if (!n.is_string()) ff.Fail("at_bound", "holds a non-name");
      for (std::size_t i = 0; i < r.param_names.size(); ++i) {
        if (n.get<std::string>() == r.param_names[i]) r.at_bound[i] = true;
      }
    }
  }
  e.chosen = ff.Bool(fj, "chosen", false);
  e.choice = ff.String(fj, "choice", "");
  const nlohmann::json options = ff.Object(fj, "options");
  e.options = options.empty() ? "" : options.dump();
  if (IsFactorizationModel(r.model)) {
    // A factorization among the candidates (io/fit_report.h): no parameters, its sidecar.
    if (!r.params.empty()) ff.Fail("params", "is not empty: a factorization has none");
    // A failed one (its solve, or its files) may have no textures to describe.
    if (!r.Failed() || fj.contains("factorization")) {
      if (!fj.contains("factorization")) ff.Fail("factorization", "is missing");
      const JsonFields fz = ff.Child("factorization");
      const nlohmann::json fo = ff.Object(fj, "factorization");
      FactorizationRef ref;
      ref.form = fz.String(fo, "form", "");
      ref.sidecar = fz.String(fo, "sidecar", "");
      if (ref.form.empty()) fz.Fail("form", "is missing or empty");
      if (ref.sidecar.empty()) fz.Fail("sidecar", "is missing or empty");
      const double bytes = fz.Required(fo, "texture_bytes", 0);
      const double values = fz.Required(fo, "values", 1);
      if (bytes >= 1e15 || values >= 1e15) fz.Fail("values", "or texture_bytes is too large");
      ref.texture_bytes = static_cast<std::uint64_t>(bytes);
      ref.values = static_cast<std::uint64_t>(values);
      e.factorization = ref;
    }
  } else if (!r.Failed()) {
    const ModelInfo* m = FindModel(r.model);
    if (!m) ff.Fail("model", "is '" + PrintableExcerpt(r.model, 64) + "', not a registered model");
    std::string bad = CheckModelParamNames(*m, r.param_names);
    if (bad.empty()) bad = CheckModelParams(r.model, r.params);
    if (!bad.empty()) ff.Fail("params", "are not the model's: " + bad);
  }
  if (!r.Failed() && !fj.contains("metrics")) ff.Fail("metrics", "is missing");
  r.metrics = MetricsFromJson(ff.Object(fj, "metrics"), !r.Failed(), ff.Child("metrics"));
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
