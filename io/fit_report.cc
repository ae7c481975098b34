#include "io/fit_report.h"

#include <H5Cpp.h>
#include <fmt/core.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <tuple>

#include "core/metrics.h"
#include "io/atomic_file.h"
#include "core/error.h"
#include "io/hdf5_storage.h"

namespace brdfit {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxStringBytes = std::size_t{1} << 20;
constexpr std::size_t kMaxParams = 4096;
constexpr std::size_t kMaxEntries = std::size_t{1} << 20;

void QuietHdf5() {
  static const bool once = [] {
    H5::Exception::dontPrint();
    return true;
  }();
  (void)once;
}

// ---- writing ------------------------------------------------------------------------------

H5::DSetCreatPropList DatasetProps() {
  H5::DSetCreatPropList p;
  H5Pset_obj_track_times(p.getId(), 0);  // no timestamps: same entries, same bytes
  return p;
}

H5::Group MakeGroup(const H5::Group& parent, const std::string& name) {
  const hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
  H5Pset_obj_track_times(gcpl, 0);
  const hid_t id = H5Gcreate2(parent.getId(), name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT);
  H5Pclose(gcpl);
  if (id < 0) throw std::runtime_error("cannot create HDF5 group " + name);
  H5Gclose(id);
  return parent.openGroup(name);
}

void StringAttr(const H5::H5Object& obj, const char* name, const std::string& value) {
  const H5::StrType type(H5::PredType::C_S1, value.size() + 1);
  obj.createAttribute(name, type, H5::DataSpace(H5S_SCALAR)).write(type, value.c_str());
}

void DoubleAttr(const H5::H5Object& obj, const char* name, double v) {
  if (!std::isfinite(v)) {
    throw std::logic_error(std::string("fit report: non-finite value for ") + name);
  }
  obj.createAttribute(name, H5::PredType::IEEE_F64LE, H5::DataSpace(H5S_SCALAR))
      .write(H5::PredType::NATIVE_DOUBLE, &v);
}

void IntAttr(const H5::H5Object& obj, const char* name, std::int64_t v) {
  obj.createAttribute(name, H5::PredType::STD_I64LE, H5::DataSpace(H5S_SCALAR))
      .write(H5::PredType::NATIVE_INT64, &v);
}

void DoubleArray(const H5::Group& g, const char* name, const std::vector<double>& v) {
  for (double x : v) {
    if (!std::isfinite(x)) throw std::logic_error(std::string("fit report: non-finite ") + name);
  }
  const hsize_t dims[1] = {v.size()};
  H5::DataSet ds =
      g.createDataSet(name, H5::PredType::IEEE_F64LE, H5::DataSpace(1, dims), DatasetProps());
  if (!v.empty()) ds.write(v.data(), H5::PredType::NATIVE_DOUBLE);
}

void WriteEntry(const H5::Group& g, const FitReportEntry& e, bool timings) {
  const FitResult& r = e.result;
  StringAttr(g, "source", e.source);
  StringAttr(g, "material", e.material);
  StringAttr(g, "model", r.model);
  StringAttr(g, "options", e.options);
  StringAttr(g, "status", ToString(r.status));
  StringAttr(g, "message", r.message);
  StringAttr(g, "termination", r.termination);
  IntAttr(g, "iterations", r.iterations);
  IntAttr(g, "starts", r.starts);
  DoubleAttr(g, "init_cost", r.init_cost);
  DoubleAttr(g, "final_cost", r.final_cost);
  IntAttr(g, "fit_samples", static_cast<std::int64_t>(r.fit_samples));
  IntAttr(g, "fit_cells", static_cast<std::int64_t>(r.fit_cells));

  DoubleArray(g, "params", r.params);
  {
    H5::DataSet params = g.openDataSet("params");
    StringAttr(params, "names", nlohmann::json(r.param_names)
                                    .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    std::vector<std::uint8_t> b(r.at_bound.begin(), r.at_bound.end());
    const hsize_t dims[1] = {b.size()};
    H5::DataSet ds =
        g.createDataSet("at_bound", H5::PredType::STD_U8LE, H5::DataSpace(1, dims), DatasetProps());
    if (!b.empty()) ds.write(b.data(), H5::PredType::NATIVE_UINT8);
  }

  const FitMetrics& m = r.metrics;
  H5::Group mg = MakeGroup(g, "metrics");
  IntAttr(mg, "ok", m.ok ? 1 : 0);
  StringAttr(mg, "problem", m.problem);
  DoubleAttr(mg, "log_rmse", m.log_rmse);
  DoubleAttr(mg, "cbrt_rmse", m.cbrt_rmse);
  DoubleAttr(mg, "rel_l2", m.rel_l2);
  IntAttr(mg, "cells", static_cast<std::int64_t>(m.cells));
  DoubleAttr(mg, "total_weight", m.total_weight);
  StringAttr(mg, "weighting", m.weighting);
  DoubleAttr(mg, "cutoff_deg", m.cutoff_deg);
  H5::Group wg = MakeGroup(mg, "worst");
  IntAttr(wg, "cell", m.worst.cell);
  DoubleAttr(wg, "theta_h", m.worst.angles.theta_h);
  DoubleAttr(wg, "theta_d", m.worst.angles.theta_d);
  DoubleAttr(wg, "phi_d", m.worst.angles.phi_d);
  DoubleAttr(wg, "theta_i_deg", m.worst.theta_i_deg);
  DoubleAttr(wg, "theta_o_deg", m.worst.theta_o_deg);
  DoubleAttr(wg, "log_error", m.worst.log_error);
  DoubleArray(wg, "measured", {m.worst.measured.begin(), m.worst.measured.end()});
  DoubleArray(wg, "predicted", {m.worst.predicted.begin(), m.worst.predicted.end()});

  const SampleCounts& c = r.sample_counts;
  H5::Group sg = MakeGroup(g, "samples");
  IntAttr(sg, "cells", static_cast<std::int64_t>(c.cells));
  IntAttr(sg, "valid", static_cast<std::int64_t>(c.valid));
  IntAttr(sg, "nonfinite", static_cast<std::int64_t>(c.nonfinite));
  IntAttr(sg, "negative", static_cast<std::int64_t>(c.negative));
  IntAttr(sg, "beyond_cutoff", static_cast<std::int64_t>(c.beyond_cutoff));
  IntAttr(sg, "eligible", static_cast<std::int64_t>(c.eligible));
  IntAttr(sg, "selected", static_cast<std::int64_t>(c.selected));

  if (timings) {
    H5::Group tg = MakeGroup(g, "timing");
    DoubleAttr(tg, "load_ms", r.times.load);
    DoubleAttr(tg, "prepare_ms", r.times.prepare);
    DoubleAttr(tg, "init_ms", r.times.init);
    DoubleAttr(tg, "solve_ms", r.times.solve);
    DoubleAttr(tg, "metrics_ms", r.times.metrics);
    DoubleAttr(tg, "init_cpu_ms", r.times.init_cpu);
    DoubleAttr(tg, "solve_cpu_ms", r.times.solve_cpu);
    DoubleAttr(tg, "metrics_cpu_ms", r.times.metrics_cpu);
  }
}

// ---- reading ------------------------------------------------------------------------------

class Reader {
 public:
  explicit Reader(const fs::path& path) : path_(path) {}
  [[noreturn]] void Fail(const std::string& problem) const { throw InputError(path_, problem); }

  H5::Attribute Attr(const H5::H5Object& obj, const std::string& where, const char* name) const {
    if (!obj.attrExists(name)) Fail(fmt::format("missing attribute {}@{}", where, name));
    H5::Attribute a = obj.openAttribute(name);
    if (a.getSpace().getSimpleExtentNpoints() != 1) {
      Fail(fmt::format("{}@{} must hold a single value", where, name));
    }
    const H5::DataType t = a.getDataType();
    if (!(t.getClass() == H5T_STRING && t.isVariableStr()) &&
        t.getSize() > (t.getClass() == H5T_STRING ? kMaxStringBytes : 8)) {
      Fail(fmt::format("{}@{} has an oversized element", where, name));
    }
    return a;
  }
  std::string Str(const H5::H5Object& obj, const std::string& where, const char* name) const {
    H5::Attribute a = Attr(obj, where, name);
    if (a.getTypeClass() != H5T_STRING) Fail(fmt::format("{}@{} is not a string", where, name));
    std::string s;
    a.read(a.getStrType(), s);
    return s;
  }
  double Dbl(const H5::H5Object& obj, const std::string& where, const char* name) const {
    H5::Attribute a = Attr(obj, where, name);
    if (a.getTypeClass() != H5T_FLOAT) Fail(fmt::format("{}@{} is not a float", where, name));
    double v = 0;
    a.read(H5::PredType::NATIVE_DOUBLE, &v);
    if (!std::isfinite(v)) Fail(fmt::format("{}@{} is not finite", where, name));
    return v;
  }
  std::int64_t Int(const H5::H5Object& obj, const std::string& where, const char* name) const {
    H5::Attribute a = Attr(obj, where, name);
    if (a.getTypeClass() != H5T_INTEGER) Fail(fmt::format("{}@{} is not an integer", where, name));
    std::int64_t v = 0;
    a.read(H5::PredType::NATIVE_INT64, &v);
    return v;
  }
  std::size_t Count(const H5::H5Object& obj, const std::string& where, const char* name) const {
    const std::int64_t v = Int(obj, where, name);
    if (v < 0) Fail(fmt::format("{}@{} is negative", where, name));
    return static_cast<std::size_t>(v);
  }
  H5::Group Group(const H5::Group& parent, const std::string& where,
                  const std::string& name) const {
    if (!parent.nameExists(name)) Fail(fmt::format("missing group {}/{}", where, name));
    return parent.openGroup(name);
  }
  std::vector<double> Doubles(const H5::Group& g, const std::string& where, const char* name,
                              std::size_t max) const {
    if (!g.nameExists(name)) Fail(fmt::format("missing dataset {}/{}", where, name));
    H5::DataSet ds = g.openDataSet(name);
    const H5::DataSpace space = ds.getSpace();
    if (ds.getTypeClass() != H5T_FLOAT || ds.getDataType().getSize() > 8 ||
        space.getSimpleExtentNdims() != 1) {
      Fail(fmt::format("dataset {}/{} must be a 1-D float array", where, name));
    }
    hsize_t n = 0;
    space.getSimpleExtentDims(&n);
    if (n > max) Fail(fmt::format("dataset {}/{} is too long", where, name));
    if (const std::string why = DamagedStorage(ds); !why.empty()) {
      Fail(fmt::format("dataset {}/{} is damaged: {}", where, name, why));
    }
    std::vector<double> v(n);
    if (n > 0) ds.read(v.data(), H5::PredType::NATIVE_DOUBLE);
    for (double x : v) {
      if (!std::isfinite(x))
        Fail(fmt::format("dataset {}/{} holds a non-finite value", where, name));
    }
    return v;
  }

  FitReportEntry Entry(const H5::Group& g, const std::string& where) const {
    FitReportEntry e;
    FitResult& r = e.result;
    e.source = Str(g, where, "source");
    e.material = Str(g, where, "material");
    r.model = Str(g, where, "model");
    e.options = Str(g, where, "options");
    // FitParamsJson parses it (fuzz/regressions/fit_report/crafted-options-not-json.h5 made it
    // throw json::parse_error out of `brdfit fit --json`).
    if (!e.options.empty() && !nlohmann::json::accept(e.options)) {
      Fail(fmt::format("{}@options is not JSON", where));
    }
    const std::string status = Str(g, where, "status");
    if (status == "converged") {
      r.status = FitStatus::kConverged;
    } else if (status == "no_convergence") {
      r.status = FitStatus::kNoConvergence;
    } else if (status == "failed") {
      r.status = FitStatus::kFailed;
    } else {
      Fail(fmt::format("{}@status is '{}'", where, status));
    }
    r.message = Str(g, where, "message");
    r.termination = Str(g, where, "termination");
    r.iterations = static_cast<int>(Int(g, where, "iterations"));
    r.starts = static_cast<int>(Int(g, where, "starts"));
    r.init_cost = Dbl(g, where, "init_cost");
    r.final_cost = Dbl(g, where, "final_cost");
    r.fit_samples = Count(g, where, "fit_samples");
    r.fit_cells = Count(g, where, "fit_cells");

    r.params = Doubles(g, where, "params", kMaxParams);
    const std::string names = Str(g.openDataSet("params"), where + "/params", "names");
    try {
      r.param_names = nlohmann::json::parse(names).get<std::vector<std::string>>();
    } catch (const nlohmann::json::exception&) {
      Fail(fmt::format("{}/params@names is not a JSON array of strings", where));
    }
    if (r.param_names.size() != r.params.size()) {
      Fail(fmt::format("{}/params: {} names for {} values", where, r.param_names.size(),
                       r.params.size()));
    }
    if (!g.nameExists("at_bound")) Fail(fmt::format("missing dataset {}/at_bound", where));
    H5::DataSet ab = g.openDataSet("at_bound");
    // Element size bounded like everything else read here (fuzz_fit_report: an integer type of
    // gigabytes per element made libhdf5 calloc its conversion buffer).
    if (ab.getTypeClass() != H5T_INTEGER || ab.getDataType().getSize() > 8 ||
        ab.getSpace().getSimpleExtentNpoints() != static_cast<hssize_t>(r.params.size())) {
      Fail(fmt::format("{}/at_bound must be {} integers", where, r.params.size()));
    }
    if (const std::string why = DamagedStorage(ab); !why.empty()) {
      Fail(fmt::format("{}/at_bound is damaged: {}", where, why));
    }
    std::vector<std::uint8_t> b(r.params.size());
    if (!b.empty()) ab.read(b.data(), H5::PredType::NATIVE_UINT8);
    r.at_bound.assign(b.begin(), b.end());

    const std::string mw = where + "/metrics";
    const H5::Group mg = Group(g, where, "metrics");
    FitMetrics& m = r.metrics;
    m.ok = Int(mg, mw, "ok") != 0;
    m.problem = Str(mg, mw, "problem");
    m.log_rmse = Dbl(mg, mw, "log_rmse");
    m.cbrt_rmse = Dbl(mg, mw, "cbrt_rmse");
    m.rel_l2 = Dbl(mg, mw, "rel_l2");
    m.cells = Count(mg, mw, "cells");
    m.total_weight = Dbl(mg, mw, "total_weight");
    m.weighting = Str(mg, mw, "weighting");
    m.cutoff_deg = Dbl(mg, mw, "cutoff_deg");
    const std::string ww = mw + "/worst";
    const H5::Group wg = Group(mg, mw, "worst");
    m.worst.cell = static_cast<std::uint32_t>(Count(wg, ww, "cell"));
    m.worst.angles = {Dbl(wg, ww, "theta_h"), Dbl(wg, ww, "theta_d"), Dbl(wg, ww, "phi_d")};
    m.worst.theta_i_deg = Dbl(wg, ww, "theta_i_deg");
    m.worst.theta_o_deg = Dbl(wg, ww, "theta_o_deg");
    m.worst.log_error = Dbl(wg, ww, "log_error");
    const std::vector<double> meas = Doubles(wg, ww, "measured", 3);
    const std::vector<double> pred = Doubles(wg, ww, "predicted", 3);
    if (meas.size() != 3 || pred.size() != 3) Fail(ww + ": measured/predicted must hold 3 values");
    std::copy(meas.begin(), meas.end(), m.worst.measured.begin());
    std::copy(pred.begin(), pred.end(), m.worst.predicted.begin());

    const std::string sw = where + "/samples";
    const H5::Group sg = Group(g, where, "samples");
    SampleCounts& c = r.sample_counts;
    c.cells = Count(sg, sw, "cells");
    c.valid = Count(sg, sw, "valid");
    c.nonfinite = Count(sg, sw, "nonfinite");
    c.negative = Count(sg, sw, "negative");
    c.beyond_cutoff = Count(sg, sw, "beyond_cutoff");
    c.eligible = Count(sg, sw, "eligible");
    c.selected = Count(sg, sw, "selected");

    if (g.nameExists("timing")) {
      const std::string tw = where + "/timing";
      const H5::Group tg = g.openGroup("timing");
      r.times.load = Dbl(tg, tw, "load_ms");
      r.times.prepare = Dbl(tg, tw, "prepare_ms");
      r.times.init = Dbl(tg, tw, "init_ms");
      r.times.solve = Dbl(tg, tw, "solve_ms");
      r.times.metrics = Dbl(tg, tw, "metrics_ms");
      r.times.init_cpu = Dbl(tg, tw, "init_cpu_ms");
      r.times.solve_cpu = Dbl(tg, tw, "solve_cpu_ms");
      r.times.metrics_cpu = Dbl(tg, tw, "metrics_cpu_ms");
    }
    return e;
  }

  std::vector<FitReportEntry> Read() const {
    H5::H5File f;
    try {
      f.openFile(path_.string(), H5F_ACC_RDONLY);
    } catch (const H5::Exception&) {
      Fail("is not a readable HDF5 file");
    }
    const std::string format = Str(f, "/", "format");
    if (format != kFitReportFormat) {
      Fail(fmt::format("format is '{}', expected '{}'", format, kFitReportFormat));
    }
    const std::int64_t version = Int(f, "/", "format_version");
    if (version != kFitReportVersion) {
      Fail(fmt::format("format_version {} is not supported (this brdfit reads {})", version,
                       kFitReportVersion));
    }
    const H5::Group entries = Group(f, "", "entries");
    const hsize_t n = entries.getNumObjs();
    if (n > kMaxEntries) Fail("too many entries");
    std::vector<FitReportEntry> out;
    for (hsize_t i = 0; i < n; ++i) {
      const std::string name = entries.getObjnameByIdx(i);
      out.push_back(Entry(entries.openGroup(name), "/entries/" + name));
    }
    return out;
  }

 private:
  fs::path path_;
};

}  // namespace

void SortEntries(std::vector<FitReportEntry>& entries) {
  std::stable_sort(entries.begin(), entries.end(),
                   [](const FitReportEntry& a, const FitReportEntry& b) {
                     return std::tie(a.source, a.result.model, a.options) <
                            std::tie(b.source, b.result.model, b.options);
                   });
}

void WriteFitReport(std::vector<FitReportEntry> entries, const fs::path& path,
                    bool include_timings) {
  QuietHdf5();
  SortEntries(entries);
  WriteFileAtomically(path, [&](const fs::path& tmp) {
    try {
      H5::FileCreatPropList fcpl;
      H5Pset_obj_track_times(fcpl.getId(), 0);  // the root group too
      H5::H5File f(tmp.string(), H5F_ACC_TRUNC, fcpl);
      StringAttr(f, "format", kFitReportFormat);
      IntAttr(f, "format_version", kFitReportVersion);
      StringAttr(f, "metrics_definition", MetricsDefinition());
      H5::Group root = f.openGroup("/");
      H5::Group g = MakeGroup(root, "entries");
      for (std::size_t i = 0; i < entries.size(); ++i) {
        WriteEntry(MakeGroup(g, fmt::format("{:05d}", i)), entries[i], include_timings);
      }
    } catch (const H5::Exception& e) {
      throw OutputError(path, "HDF5: " + e.getDetailMsg());
    }
  });
}

std::vector<FitReportEntry> ReadFitReport(const fs::path& path) {
  QuietHdf5();
  if (!fs::exists(path)) throw InputError(path, "no such file");
  try {
    return Reader(path).Read();
  } catch (const H5::Exception& e) {
    throw InputError(path, "HDF5: " + e.getDetailMsg());
  }
}

std::string FitParamsJson(std::vector<FitReportEntry> entries) {
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
    j["metrics"] = {{"log_rmse", r.metrics.log_rmse},
                    {"cbrt_rmse", r.metrics.cbrt_rmse},
                    {"rel_l2", r.metrics.rel_l2},
                    {"weighting", r.metrics.weighting},
                    {"cutoff_deg", r.metrics.cutoff_deg}};
    j["options"] = nlohmann::ordered_json::parse(e.options.empty() ? "{}" : e.options);
    fits.push_back(j);
  }
  nlohmann::ordered_json root;
  root["format"] = "brdfit-fit-params";
  root["format_version"] = 1;
  root["fits"] = fits;
  // Strings come from file names and from reports written elsewhere: bytes that are not UTF-8
  // become U+FFFD instead of throwing json::type_error 316 (fuzz_fit_report; a table named
  // "caf\xe9.binary" made `brdfit fit --json` fail after fitting).
  return root.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace brdfit
