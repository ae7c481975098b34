#include "io/fit_report.h"

#include <H5Cpp.h>
#include <fmt/core.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "core/error.h"
#include "core/metrics.h"
#include "core/model_params.h"
#include "core/provenance.h"
#include "io/hdf5_util.h"
#include "io/input_file.h"
#include "io/metrics_json.h"
#include "models/registry.h"

namespace brdfit {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxParams = 4096;
constexpr std::size_t kMaxEntries = std::size_t{1} << 20;

using hdf5::WriteIntAttr;
using hdf5::WriteStringAttr;

// ---- writing ------------------------------------------------------------------------------

H5::Group MakeGroup(const H5::Group& parent, const std::string& name) {
  const hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
  H5Pset_obj_track_times(gcpl, 0);
  const hid_t id = H5Gcreate2(parent.getId(), name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT);
  H5Pclose(gcpl);
  if (id < 0) throw std::runtime_error("cannot create HDF5 group " + name);
  H5Gclose(id);
  return parent.openGroup(name);
}

// FitResult holds no NaN or Inf (core/result.h): one here is a bug, not bad input.
void DoubleAttr(const H5::H5Object& obj, const char* name, double v) {
  if (!std::isfinite(v)) {
    throw std::logic_error(std::string("fit report: non-finite value for ") + name);
  }
  hdf5::WriteDoubleAttr(obj, name, v);
}

void DoubleArray(const H5::Group& g, const char* name, const std::vector<double>& v) {
  for (double x : v) {
    if (!std::isfinite(x)) throw std::logic_error(std::string("fit report: non-finite ") + name);
  }
  hdf5::WriteDoubles(g, name, v);
}

// The rendered-image metric (docs/accuracy.md): /metrics/rendered, with per-light arrays; left
// out when it was not computed (a failed fit).
void WriteRendered(const H5::Group& mg, const RenderedError& e) {
  if (e.num_lights == 0) return;
  H5::Group rg = MakeGroup(mg, "rendered");
  WriteIntAttr(rg, "ok", e.ok ? 1 : 0);
  WriteStringAttr(rg, "problem", e.problem);
  for (const RenderedSummaryField& f : kRenderedSummary) {
    if (f.NotComputed(e)) continue;
    DoubleAttr(rg, f.name, e.*f.value);
  }
  WriteIntAttr(rg, "resolution", e.resolution);
  WriteIntAttr(rg, "lit_pixels", static_cast<std::int64_t>(e.lit_pixels));
  WriteIntAttr(rg, "masked_pixels", static_cast<std::int64_t>(e.masked_pixels));
  WriteIntAttr(rg, "compared_pixels", static_cast<std::int64_t>(e.compared_pixels));
  std::vector<double> deg, psnr, median;
  for (int k = 0; k < e.num_lights; ++k) {
    deg.push_back(e.lights[k].light_deg);
    psnr.push_back(e.lights[k].psnr_db);
    median.push_back(e.lights[k].median_rel_error);
  }
  DoubleArray(rg, "light_deg", deg);
  DoubleArray(rg, "light_psnr_db", psnr);
  DoubleArray(rg, "light_median_rel_error", median);
  // Per region (core/rendered_regions.h: front, side, rim, environment); lights 0 where none.
  std::vector<double> region_lights, region_psnr, region_median;
  for (const RenderedRegionError& g : e.regions) {
    region_lights.push_back(g.lights);
    region_psnr.push_back(g.psnr_db);
    region_median.push_back(g.median_rel_error);
  }
  DoubleArray(rg, "region_lights", region_lights);
  DoubleArray(rg, "region_psnr_db", region_psnr);
  DoubleArray(rg, "region_median_rel_error", region_median);
}

void WriteEntry(const H5::Group& g, const FitReportEntry& e, bool timings) {
  const FitResult& r = e.result;
  WriteStringAttr(g, "source", e.source);
  WriteStringAttr(g, "material", e.material);
  WriteStringAttr(g, "model", r.model);
  WriteStringAttr(g, "options", e.options);
  WriteStringAttr(g, "status", ToString(r.status));
  WriteStringAttr(g, "message", r.message);
  WriteStringAttr(g, "termination", r.termination);
  WriteIntAttr(g, "chosen", e.chosen ? 1 : 0);
  WriteStringAttr(g, "choice", e.choice);
  if (!e.source_hash.empty()) WriteStringAttr(g, "source_hash", e.source_hash);
  for (const FitNumberField& n : kFitNumbers) {
    if (n.value) {
      DoubleAttr(g, n.name, r.*n.value);
    } else {
      WriteIntAttr(g, n.name, n.small ? r.*n.small : static_cast<std::int64_t>(r.*n.count));
    }
  }

  DoubleArray(g, "params", r.params);
  {
    H5::DataSet params = g.openDataSet("params");
    WriteStringAttr(params, "names",
                    nlohmann::json(r.param_names)
                        .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    const std::vector<std::uint8_t> b(r.at_bound.begin(), r.at_bound.end());
    hdf5::WriteDataset(g, "at_bound", H5::PredType::STD_U8LE, H5::PredType::NATIVE_UINT8,
                       {b.size()}, b.data());
  }

  const FitMetrics& m = r.metrics;
  H5::Group mg = MakeGroup(g, "metrics");
  WriteIntAttr(mg, "ok", m.ok ? 1 : 0);
  WriteStringAttr(mg, "problem", m.problem);
  for (const ErrorMetricField& f : kErrorMetrics) DoubleAttr(mg, f.name, m.*f.value);
  WriteIntAttr(mg, "cells", static_cast<std::int64_t>(m.cells));
  DoubleAttr(mg, "total_weight", m.total_weight);
  WriteStringAttr(mg, "weighting", m.weighting);
  DoubleAttr(mg, "cutoff_deg", m.cutoff_deg);
  H5::Group wg = MakeGroup(mg, "worst");
  WriteIntAttr(wg, "cell", m.worst.cell);
  DoubleAttr(wg, "theta_h", m.worst.angles.theta_h);
  DoubleAttr(wg, "theta_d", m.worst.angles.theta_d);
  DoubleAttr(wg, "phi_d", m.worst.angles.phi_d);
  DoubleAttr(wg, "theta_i_deg", m.worst.theta_i_deg);
  DoubleAttr(wg, "theta_o_deg", m.worst.theta_o_deg);
  DoubleAttr(wg, "log_error", m.worst.log_error);
  DoubleArray(wg, "measured", {m.worst.measured.begin(), m.worst.measured.end()});
  DoubleArray(wg, "predicted", {m.worst.predicted.begin(), m.worst.predicted.end()});

  WriteRendered(mg, m.rendered);

  const SampleCounts& c = r.sample_counts;
  H5::Group sg = MakeGroup(g, "samples");
  for (const SampleCountField& s : kSampleCountFields) {
    WriteIntAttr(sg, s.name, static_cast<std::int64_t>(c.*s.value));
  }

  if (e.factorization) {
    const FactorizationRef& f = *e.factorization;
    H5::Group fg = MakeGroup(g, "factorization");
    WriteStringAttr(fg, "form", f.form);
    WriteStringAttr(fg, "sidecar", f.sidecar);
    WriteIntAttr(fg, "texture_bytes", static_cast<std::int64_t>(f.texture_bytes));
    WriteIntAttr(fg, "values", static_cast<std::int64_t>(f.values));
  }

  if (timings) {
    H5::Group tg = MakeGroup(g, "timing");
    for (const FitTimeField& t : kFitTimeFields) DoubleAttr(tg, t.name, r.times.*t.value);
  }
}

// ---- reading ------------------------------------------------------------------------------

class Reader : public hdf5::Reader {
 public:
  using hdf5::Reader::Reader;

  std::size_t Count(const H5::H5Object& obj, const std::string& where, const char* name) const {
    const std::int64_t v = Int(obj, where, name);
    if (v < 0) Fail(fmt::format("{}@{} is negative", where, name));
    return static_cast<std::size_t>(v);
  }
  // An int attribute in [0, INT_MAX] (iterations, starts: a cast of -3 or 2^40 was kept).
  int SmallCount(const H5::H5Object& obj, const std::string& where, const char* name) const {
    const std::int64_t v = Int(obj, where, name);
    if (v < 0 || v > std::numeric_limits<int>::max()) {
      Fail(fmt::format("{}@{} is {}, outside [0, {}]", where, name, v,
                       std::numeric_limits<int>::max()));
    }
    return static_cast<int>(v);
  }
  // A finite double attribute >= 0 (costs, errors, weights, times).
  double NonNegative(const H5::H5Object& obj, const std::string& where, const char* name) const {
    const double v = Double(obj, where, name);
    if (v < 0) Fail(fmt::format("{}@{} is {}, below 0", where, name, v));
    return v;
  }
  // A finite double attribute in [lo, hi].
  double InRange(const H5::H5Object& obj, const std::string& where, const char* name, double lo,
                 double hi) const {
    const double v = Double(obj, where, name);
    if (v < lo || v > hi)
      Fail(fmt::format("{}@{} is {}, outside [{}, {}]", where, name, v, lo, hi));
    return v;
  }
  // A 1-D array of at most max finite floats.
  void ReadRendered(const H5::Group& rg, const std::string& rw, RenderedError* e) const {
    e->ok = Int(rg, rw, "ok") != 0;
    e->problem = String(rg, rw, "problem");
    for (const RenderedSummaryField& f : kRenderedSummary) {
      if (!f.required && !rg.attrExists(f.name)) {
        e->*f.value = std::numeric_limits<double>::quiet_NaN();  // written before it existed
        continue;
      }
      e->*f.value = Double(rg, rw, f.name);
      if (e->*f.value < f.min_value)
        Fail(fmt::format("{}@{} is {}, below {}", rw, f.name, e->*f.value, f.min_value));
    }
    e->resolution = static_cast<int>(Count(rg, rw, "resolution"));
    e->lit_pixels = Count(rg, rw, "lit_pixels");
    e->masked_pixels = Count(rg, rw, "masked_pixels");
    e->compared_pixels = Count(rg, rw, "compared_pixels");
    const std::vector<double> deg = Doubles(rg, rw, "light_deg", kRenderedMaxLights);
    const std::vector<double> psnr = Doubles(rg, rw, "light_psnr_db", kRenderedMaxLights);
    const std::vector<double> med = Doubles(rg, rw, "light_median_rel_error", kRenderedMaxLights);
    if (psnr.size() != deg.size() || med.size() != deg.size()) {
      Fail(rw + ": light_deg, light_psnr_db and light_median_rel_error differ in length");
    }
    e->num_lights = static_cast<int>(deg.size());
    for (std::size_t k = 0; k < deg.size(); ++k) {
      e->lights[k].light_deg = deg[k];
      e->lights[k].psnr_db = psnr[k];
      e->lights[k].median_rel_error = med[k];
    }
    // Reports written before the metric had regions have none (core/rendered_regions.h then
    // derives them from the lights).
    if (H5Lexists(rg.getId(), "region_lights", H5P_DEFAULT) > 0) {
      const std::vector<double> lights = Doubles(rg, rw, "region_lights", kRenderedRegions);
      const std::vector<double> rpsnr = Doubles(rg, rw, "region_psnr_db", kRenderedRegions);
      const std::vector<double> rmed = Doubles(rg, rw, "region_median_rel_error", kRenderedRegions);
      // Reports written before the environment region hold the three directional ones.
      const std::size_t n = lights.size();
      if ((n != kRenderedRegions && n != kRenderedRegions - 1) || rpsnr.size() != n ||
          rmed.size() != n) {
        Fail(
            fmt::format("{}: region_lights, region_psnr_db and region_median_rel_error must hold "
                        "{} values (or {}, without the environment)",
                        rw, kRenderedRegions, kRenderedRegions - 1));
      }
      for (std::size_t g = 0; g < n; ++g) {
        if (!(lights[g] >= 0 && lights[g] <= kRenderedMaxLights) ||
            lights[g] != std::floor(lights[g]) || rmed[g] < 0) {
          Fail(fmt::format("{}: region {} holds {} lights and median {}", rw, g, lights[g],
                           rmed[g]));
        }
        e->regions[g] = {static_cast<int>(lights[g]), rpsnr[g], rmed[g]};
      }
    }
  }

  std::vector<double> Doubles(const H5::Group& g, const std::string& where, const char* name,
                              std::size_t max) const {
    std::vector<hsize_t> dims;
    const H5::DataSet ds = Dataset(g, where, name, H5T_FLOAT, &dims);
    const std::string what = "dataset " + hdf5::Join(where, name);
    if (dims.size() != 1) Fail(what + " must be a 1-D float array");
    if (dims[0] > max) Fail(what + " is too long");
    return ReadFinite(ds, what);
  }

  // The model's parameters, by name and in its bounds (1e300 crashed the renderer); a failed
  // fit holds the initial guess or zeros (core/result.h), or none.
  void CheckParams(const ModelInfo& model, const FitResult& r, const std::string& where) const {
    if (r.Failed() ? !r.params.empty() && r.params.size() != model.params.size()
                   : r.params.size() != model.params.size()) {
      Fail(fmt::format("{}/params: {} values, model {} has {} parameters", where, r.params.size(),
                       r.model, model.params.size()));
    }
    if (!r.params.empty()) {
      if (const std::string bad = CheckModelParamNames(model, r.param_names); !bad.empty()) {
        Fail(fmt::format("{}/params@names: {}", where, bad));
      }
    }
    if (!r.Failed()) {
      if (const std::string bad = CheckModelParams(r.model, r.params); !bad.empty()) {
        Fail(fmt::format("{}/params: {}", where, bad));
      }
    }
  }

  FactorizationRef Factorization(const H5::Group& g, const std::string& where) const {
    const std::string fw = where + "/factorization";
    const H5::Group fg = Group(g, where, "factorization");
    FactorizationRef f;
    f.form = String(fg, fw, "form");
    f.sidecar = String(fg, fw, "sidecar");
    if (f.form.empty() || f.sidecar.empty()) Fail(fw + ": form and sidecar must not be empty");
    f.texture_bytes = Count(fg, fw, "texture_bytes");
    f.values = Count(fg, fw, "values");
    if (f.values == 0) Fail(fw + "@values must be positive");
    return f;
  }

  FitReportEntry Entry(const H5::Group& g, const std::string& where) const {
    FitReportEntry e;
    FitResult& r = e.result;
    e.source = String(g, where, "source");
    e.material = String(g, where, "material");
    r.model = String(g, where, "model");
    const bool factorization = r.model == kFactorizationModel;
    const ModelInfo* model = factorization ? nullptr : FindModel(r.model);
    if (!model && !factorization) Fail(fmt::format("{}@model: unknown model '{}'", where, r.model));
    e.options = String(g, where, "options");
    // FitParamsJson parses it (fuzz/regressions/fit_report/crafted-options-not-json.h5 made it
    // throw json::parse_error out of `brdfit fit --json`).
    if (!e.options.empty() && !nlohmann::json::accept(e.options)) {
      Fail(fmt::format("{}@options is not JSON", where));
    }
    const std::string status = String(g, where, "status");
    const std::optional<FitStatus> known = kFitStatusNames.Find(status);
    if (!known) Fail(fmt::format("{}@status is '{}'", where, status));
    r.status = *known;
    r.message = String(g, where, "message");
    r.termination = String(g, where, "termination");
    // Reports written before the model choice have neither attribute.
    if (g.attrExists("chosen")) {
      const std::int64_t chosen = Int(g, where, "chosen");
      if (chosen != 0 && chosen != 1) Fail(fmt::format("{}@chosen must be 0 or 1", where));
      e.chosen = chosen == 1;
    }
    if (g.attrExists("choice")) e.choice = String(g, where, "choice");
    if (g.attrExists("source_hash")) e.source_hash = String(g, where, "source_hash");
    for (const FitNumberField& n : kFitNumbers) {
      if (n.value) {
        r.*n.value = NonNegative(g, where, n.name);
      } else if (n.small) {
        r.*n.small = SmallCount(g, where, n.name);
      } else {
        r.*n.count = Count(g, where, n.name);
      }
    }

    r.params = Doubles(g, where, "params", kMaxParams);
    const std::string names = String(g.openDataSet("params"), where + "/params", "names");
    try {
      r.param_names = nlohmann::json::parse(names).get<std::vector<std::string>>();
    } catch (const nlohmann::json::exception&) {
      Fail(fmt::format("{}/params@names is not a JSON array of strings", where));
    }
    if (r.param_names.size() != r.params.size()) {
      Fail(fmt::format("{}/params: {} names for {} values", where, r.param_names.size(),
                       r.params.size()));
    }
    if (factorization) {
      // A factorization has no parameters: its textures are files (FactorizationRef).
      if (!r.params.empty()) Fail(fmt::format("{}/params: a factorization has none", where));
      // A failed one (its solve, or its files) may have no textures to describe.
      if (!r.Failed() || g.nameExists("factorization")) e.factorization = Factorization(g, where);
    } else {
      if (g.nameExists("factorization")) {
        Fail(fmt::format("{}/factorization: the entry is a fit of {}", where, r.model));
      }
      CheckParams(*model, r, where);
    }
    std::vector<hsize_t> dims;
    const H5::DataSet ab = Dataset(g, where, "at_bound", H5T_INTEGER, &dims);
    if (ab.getSpace().getSimpleExtentNpoints() != static_cast<hssize_t>(r.params.size())) {
      Fail(fmt::format("{}/at_bound must be {} integers", where, r.params.size()));
    }
    std::vector<std::uint8_t> b(r.params.size());
    ReadChecked(ab, "dataset " + where + "/at_bound", H5::PredType::NATIVE_UINT8, b.data());
    r.at_bound.assign(b.begin(), b.end());

    const std::string mw = where + "/metrics";
    const H5::Group mg = Group(g, where, "metrics");
    FitMetrics& m = r.metrics;
    m.ok = Int(mg, mw, "ok") != 0;
    m.problem = String(mg, mw, "problem");
    for (const ErrorMetricField& f : kErrorMetrics) m.*f.value = NonNegative(mg, mw, f.name);
    m.cells = Count(mg, mw, "cells");
    m.total_weight = NonNegative(mg, mw, "total_weight");
    m.weighting = String(mg, mw, "weighting");
    m.cutoff_deg = InRange(mg, mw, "cutoff_deg", 0, 90);
    const std::string ww = mw + "/worst";
    const H5::Group wg = Group(mg, mw, "worst");
    m.worst.cell = static_cast<std::uint32_t>(Count(wg, ww, "cell"));
    // Angles of a cell of the (theta_h, theta_d, phi_d) grid, phi_d either way round.
    m.worst.angles = {InRange(wg, ww, "theta_h", 0, kPi / 2),
                      InRange(wg, ww, "theta_d", 0, kPi / 2),
                      InRange(wg, ww, "phi_d", -2 * kPi, 2 * kPi)};
    m.worst.theta_i_deg = InRange(wg, ww, "theta_i_deg", 0, 180);
    m.worst.theta_o_deg = InRange(wg, ww, "theta_o_deg", 0, 180);
    m.worst.log_error = Double(wg, ww, "log_error");
    const std::vector<double> meas = Doubles(wg, ww, "measured", 3);
    const std::vector<double> pred = Doubles(wg, ww, "predicted", 3);
    if (meas.size() != 3 || pred.size() != 3) Fail(ww + ": measured/predicted must hold 3 values");
    std::copy(meas.begin(), meas.end(), m.worst.measured.begin());
    std::copy(pred.begin(), pred.end(), m.worst.predicted.begin());
    // Reports written before the rendered-image metric have no /metrics/rendered.
    if (H5Lexists(mg.getId(), "rendered", H5P_DEFAULT) > 0) {
      ReadRendered(Group(mg, mw, "rendered"), mw + "/rendered", &m.rendered);
    }

    const std::string sw = where + "/samples";
    const H5::Group sg = Group(g, where, "samples");
    SampleCounts& c = r.sample_counts;
    for (const SampleCountField& s : kSampleCountFields) c.*s.value = Count(sg, sw, s.name);

    if (g.nameExists("timing")) {
      e.timed = true;
      const std::string tw = where + "/timing";
      const H5::Group tg = Group(g, where, "timing");
      for (const FitTimeField& t : kFitTimeFields) {
        r.times.*t.value = NonNegative(tg, tw, t.name);
      }
    }
    return e;
  }

  std::vector<FitReportEntry> Read() const {
    const H5::H5File f = Open();
    const std::string format = String(f, "/", "format");
    if (format != kFitReportFormat) {
      Fail(fmt::format("format is '{}', expected '{}'", format, kFitReportFormat));
    }
    const std::int64_t version = Int(f, "/", "format_version");
    if (version != kFitReportVersion) {
      Fail(fmt::format("format_version {} is not supported (this brdfit reads {})", version,
                       kFitReportVersion));
    }
    const H5::Group entries = Group(f, "/", "entries");
    const hsize_t n = entries.getNumObjs();
    if (n > kMaxEntries) Fail("too many entries");
    std::vector<FitReportEntry> out;
    std::vector<std::string> names;
    for (hsize_t i = 0; i < n; ++i) {
      names.push_back(entries.getObjnameByIdx(i));
      out.push_back(Entry(Group(entries, "/entries", names.back()), "/entries/" + names.back()));
    }
    if (const auto two = TwoChosenOfOneMaterial(out)) {
      Fail(fmt::format(
          "/entries/{} and /entries/{} are both chosen for material '{}' (a report "
          "chooses one fit per material)",
          PrintableExcerpt(names[two->first], 64), PrintableExcerpt(names[two->second], 64),
          PrintableExcerpt(out[two->second].material, 64)));
    }
    return out;
  }
  // The root's brdfit_version ("" when absent); the format is checked as by Read().
  std::string WriterVersion() const {
    const H5::H5File f = Open();
    if (String(f, "/", "format") != kFitReportFormat) Fail("not a fit report");
    return f.attrExists("brdfit_version") ? String(f, "/", "brdfit_version") : std::string();
  }
};

}  // namespace

std::string ReadFitReportWriterVersion(const fs::path& path) {
  try {
    return Reader(path).WriterVersion();
  } catch (const H5::Exception& e) {
    throw InputError(path, hdf5::Describe(e));
  }
}

FitReportEntry NewFactorizationEntry(std::string source, std::string material, std::string options,
                                     std::string source_hash) {
  FitReportEntry e;
  e.source = std::move(source);
  e.material = std::move(material);
  e.options = std::move(options);
  e.source_hash = std::move(source_hash);
  e.result.model = kFactorizationModel;
  return e;
}

void SortEntries(std::vector<FitReportEntry>& entries) {
  std::stable_sort(entries.begin(), entries.end(),
                   [](const FitReportEntry& a, const FitReportEntry& b) {
                     return std::tie(a.source, a.result.model, a.options) <
                            std::tie(b.source, b.result.model, b.options);
                   });
}

void WriteFitReport(std::vector<FitReportEntry> entries, const fs::path& path,
                    bool include_timings) {
  hdf5::Quiet();
  SortEntries(entries);
  H5::FileCreatPropList fcpl;
  H5Pset_obj_track_times(fcpl.getId(), 0);  // the root group too
  // Built in memory, written with every write checked (a full disk: OutputError, the previous
  // report left as it was).
  hdf5::WriteFileImageAtomically(
      path,
      [&](H5::H5File& f) {
        WriteStringAttr(f, "format", kFitReportFormat);
        WriteIntAttr(f, "format_version", kFitReportVersion);
        WriteStringAttr(f, "metrics_definition", MetricsDefinition());
        const RunProvenance run = CurrentRunProvenance(include_timings);
        WriteStringAttr(f, "brdfit_version", run.version);
        if (!run.command_line.empty()) WriteStringAttr(f, "command_line", run.command_line);
        if (!run.created.empty()) WriteStringAttr(f, "created", run.created);
        H5::Group root = f.openGroup("/");
        H5::Group g = MakeGroup(root, "entries");
        for (std::size_t i = 0; i < entries.size(); ++i) {
          WriteEntry(MakeGroup(g, fmt::format("{:05d}", i)), entries[i], include_timings);
        }
      },
      fcpl);
}

std::vector<FitReportEntry> ReadFitReport(const fs::path& path) {
  try {
    return Reader(path).Read();
  } catch (const H5::Exception& e) {
    throw InputError(path, hdf5::Describe(e));
  }
}

std::optional<std::pair<std::size_t, std::size_t>> TwoChosenOfOneMaterial(
    const std::vector<FitReportEntry>& entries) {
  std::map<std::string, std::size_t> chosen_at;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (!entries[i].chosen) continue;
    const auto [it, first] = chosen_at.emplace(entries[i].material, i);
    if (!first) return std::make_pair(it->second, i);
  }
  return std::nullopt;
}

std::string FitParamsJson(std::vector<FitReportEntry> entries, bool run_details) {
  SortEntries(entries);
  nlohmann::ordered_json fits = nlohmann::ordered_json::array();
  for (const FitReportEntry& e : entries) {
    const FitResult& r = e.result;
    nlohmann::ordered_json j;
    j["source"] = e.source;
    j["material"] = e.material;
    j["model"] = r.model;
    j["status"] = ToString(r.status);
    j["message"] = r.message;
    nlohmann::ordered_json params = nlohmann::ordered_json::object();
    for (std::size_t i = 0; i < r.params.size(); ++i) params[r.param_names[i]] = r.params[i];
    j["params"] = params;
    // The parameters that ended on one of their bounds, by name (the HDF5 entry's at_bound).
    nlohmann::ordered_json at_bound = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < r.params.size() && i < r.at_bound.size(); ++i) {
      if (r.at_bound[i]) at_bound.push_back(r.param_names[i]);
    }
    j["at_bound"] = at_bound;
    if (e.factorization) {
      const FactorizationRef& f = *e.factorization;
      j["factorization"] = {{"form", f.form},
                            {"sidecar", f.sidecar},
                            {"texture_bytes", f.texture_bytes},
                            {"values", f.values}};
    }
    nlohmann::ordered_json& mj = j["metrics"];
    for (const ErrorMetricField& f : kErrorMetrics) mj[f.name] = r.metrics.*f.value;
    mj["weighting"] = r.metrics.weighting;
    mj["cutoff_deg"] = r.metrics.cutoff_deg;
    if (RenderedErrorComputed(r.metrics.rendered)) {
      j["metrics"]["rendered"] = RenderedErrorJson(r.metrics.rendered);
    }
    j["chosen"] = e.chosen;
    if (e.chosen) j["choice"] = e.choice;
    j["options"] = nlohmann::ordered_json::parse(e.options.empty() ? "{}" : e.options);
    if (!e.source_hash.empty()) j["source_hash"] = e.source_hash;
    fits.push_back(j);
  }
  nlohmann::ordered_json root;
  root["format"] = "brdfit-fit-params";
  root["format_version"] = kFitParamsJsonVersion;
  root["fits"] = fits;
  const RunProvenance run = CurrentRunProvenance(run_details);
  nlohmann::ordered_json prov = {{"brdfit_version", run.version}};
  if (!run.command_line.empty()) prov["command_line"] = run.command_line;
  if (!run.created.empty()) prov["created"] = run.created;
  root["provenance"] = prov;
  // Strings come from file names and from reports written elsewhere: bytes that are not UTF-8
  // become U+FFFD instead of throwing json::type_error 316 (fuzz_fit_report; a table named
  // "caf\xe9.binary" made `brdfit fit --json` fail after fitting).
  return root.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace brdfit
