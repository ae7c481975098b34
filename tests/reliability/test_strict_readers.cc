// Strict readers (issue 14 item 14): every numeric field of a fit report range-checked on read,
// fit parameters of a registered model only, renders that decode, scenes without duplicate
// keys, HDF5 tables without links into other files, provenance that is JSON. `report` and
// `compare` exit 2 naming the file and the field; nothing is written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <H5Cpp.h>
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_process.h"
#include "core/error.h"
#include "core/synth.h"
#include "io/fit_report.h"
#include "io/hdf5_table.h"
#include "io/hdf5_util.h"
#include "io/image_io.h"
#include "models/registry.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing_cli::ReadAll;
using testing_cli::Spawn;
using testing_cli::Wait;

using testing_cli::CliRun;

CliRun RunCli(const ScratchDir& dir, const std::vector<std::string>& args) {
  return testing_cli::Run(args, dir / "run.log");
}

Table SmallTable() {
  const ModelInfo* m = FindModel("lambert+ggx");
  const std::vector<double> p = m->DefaultParams();
  return SynthesizeTable(Grid{8, 8, 16, ThetaHMapping::kSqrt},
                         [&](const Geometry& g, double rgb[3]) { m->eval(p.data(), g, rgb); }, {});
}

// One converged lambert+ggx fit of material "t" (no table beside it: the report notes that).
FitReportEntry GoodEntry() {
  const ModelInfo* m = FindModel("lambert+ggx");
  FitReportEntry e;
  e.source = "t.h5";
  e.material = "t";
  e.options = R"({"budget":"full","loss":"log"})";
  FitResult& r = e.result;
  r.model = m->name;
  r.param_names = m->param_names;
  r.params = m->DefaultParams();
  r.at_bound.assign(r.params.size(), false);
  r.status = FitStatus::kConverged;
  r.iterations = 12;
  r.starts = 1;
  r.metrics.ok = true;
  r.metrics.log_rmse = r.metrics.cbrt_rmse = r.metrics.rel_l2 = 0.01;
  r.metrics.cutoff_deg = 80;
  return e;
}

class StrictReaders : public ::testing::Test {
 protected:
  void SetUp() override { WriteFitReport({GoodEntry()}, good_); }

  // A copy of the good report with `edit` applied to its only entry.
  fs::path Damaged(const std::string& name, const std::function<void(H5::Group&)>& edit) {
    const fs::path p = dir_ / name;
    fs::copy_file(good_, p, fs::copy_options::overwrite_existing);
    H5::H5File f(p.string(), H5F_ACC_RDWR);
    H5::Group g = f.openGroup("/entries/00000");
    edit(g);
    return p;
  }

  // `report` and `compare` both refuse `bad`: exit 2, the file and `problem` named, no page.
  void ExpectRefused(const fs::path& bad, const std::string& problem) {
    const fs::path html = dir_ / "r.html";
    const CliRun r =
        RunCli(dir_, {"report", bad.string(), "--no-renders", "-q", "-o", html.string()});
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + bad.string())) << r.log;
    EXPECT_THAT(r.log, HasSubstr(problem)) << r.log;
    EXPECT_FALSE(fs::exists(html));
    const CliRun c = RunCli(dir_, {"compare", good_.string(), bad.string()});
    EXPECT_EQ(c.code, 2) << c.log;
    EXPECT_THAT(c.log, HasSubstr("brdfit: error: " + bad.string())) << c.log;
    EXPECT_THAT(c.log, HasSubstr(problem)) << c.log;
  }

  static void SetString(H5::H5Object& o, const char* name, const std::string& v) {
    o.removeAttr(name);
    hdf5::WriteStringAttr(o, name, v);
  }
  static void SetInt(H5::H5Object& o, const char* name, std::int64_t v) {
    o.removeAttr(name);
    hdf5::WriteIntAttr(o, name, v);
  }
  static void SetDouble(H5::H5Object& o, const char* name, double v) {
    o.removeAttr(name);
    hdf5::WriteDoubleAttr(o, name, v);
  }

  ScratchDir dir_;
  fs::path good_ = dir_ / "good.h5";
};

TEST_F(StrictReaders, TheGoodReportIsReadByReportAndCompare) {  // the baseline of the cases
  const CliRun r = RunCli(
      dir_, {"report", good_.string(), "--no-renders", "-q", "-o", (dir_ / "r.html").string()});
  EXPECT_EQ(r.code, 0) << r.log;
  EXPECT_EQ(RunCli(dir_, {"compare", good_.string(), good_.string()}).code, 0);
}

TEST_F(StrictReaders, ParameterNamesThatAreNotJsonOrOfTheWrongLengthOrNotTheModels) {
  ExpectRefused(Damaged("notjson.h5",
                        [](H5::Group& g) {
                          H5::DataSet ds = g.openDataSet("params");
                          SetString(ds, "names", "[\"lambert.kd_r\", oops");
                        }),
                "/entries/00000/params@names is not a JSON array of strings");
  ExpectRefused(Damaged("short.h5",
                        [](H5::Group& g) {
                          H5::DataSet ds = g.openDataSet("params");
                          SetString(ds, "names", R"(["lambert.kd_r"])");
                        }),
                "/entries/00000/params: 1 names for");
  ExpectRefused(Damaged("renamed.h5",
                        [](H5::Group& g) {
                          const ModelInfo* m = FindModel("lambert+ggx");
                          std::vector<std::string> names = m->param_names;
                          names.back() = "ggx.beta";
                          H5::DataSet ds = g.openDataSet("params");
                          SetString(ds, "names", nlohmann::json(names).dump());
                        }),
                "/entries/00000/params@names: parameter " +
                    std::to_string(FindModel("lambert+ggx")->params.size() - 1) +
                    " is 'ggx.beta', model lambert+ggx calls it '" +
                    FindModel("lambert+ggx")->param_names.back() + "'");
}

TEST_F(StrictReaders, AnUnknownModelIsRefused) {
  ExpectRefused(Damaged("model.h5", [](H5::Group& g) { SetString(g, "model", "lambert+zzz"); }),
                "/entries/00000@model: unknown model 'lambert+zzz'");
}

TEST_F(StrictReaders, NegativeCountsAndMetricsAreRefused) {
  ExpectRefused(Damaged("iter.h5", [](H5::Group& g) { SetInt(g, "iterations", -3); }),
                "/entries/00000@iterations is -3, outside [0, 2147483647]");
  ExpectRefused(Damaged("starts.h5", [](H5::Group& g) { SetInt(g, "starts", 1LL << 40); }),
                "/entries/00000@starts is 1099511627776, outside [0, 2147483647]");
  ExpectRefused(Damaged("cost.h5", [](H5::Group& g) { SetDouble(g, "final_cost", -1); }),
                "/entries/00000@final_cost is -1, below 0");
  ExpectRefused(Damaged("rmse.h5",
                        [](H5::Group& g) {
                          H5::Group mg = g.openGroup("metrics");
                          SetDouble(mg, "log_rmse", -0.5);
                        }),
                "/entries/00000/metrics@log_rmse is -0.5, below 0");
  ExpectRefused(Damaged("cutoff.h5",
                        [](H5::Group& g) {
                          H5::Group mg = g.openGroup("metrics");
                          SetDouble(mg, "cutoff_deg", 400);
                        }),
                "/entries/00000/metrics@cutoff_deg is 400, outside [0, 90]");
}

TEST_F(StrictReaders, TwoChosenFitsOfOneMaterialAreRefused) {
  // A report chooses one fit per material; with two, an export's pick would be the order's.
  FitReportEntry a = GoodEntry(), b = GoodEntry();
  a.chosen = b.chosen = true;
  b.options = R"({"budget":"full","loss":"rel"})";
  const fs::path two = dir_ / "two.h5";
  WriteFitReport({a, b}, two);
  ExpectRefused(two, "are both chosen for material 't' (a report chooses one fit per material)");
  b.chosen = false;
  WriteFitReport({a, b}, two);
  EXPECT_EQ(ReadFitReport(two).size(), 2u);
}

TEST_F(StrictReaders, ParametersOutsideTheModelsBoundsAreRefused) {
  ExpectRefused(Damaged("huge.h5",
                        [](H5::Group& g) {
                          const std::vector<double> p(FindModel("lambert+ggx")->params.size(),
                                                      1e300);
                          g.openDataSet("params").write(p.data(), H5::PredType::NATIVE_DOUBLE);
                        }),
                "/entries/00000/params: parameter lambert.kd_r = 1e+300 outside the model's "
                "bounds");
}

// A fit parameters file (brdfit fit --json) with one fit of `model` and `params`.
std::string ParamsJson(const std::string& model, const std::string& params) {
  return R"({"format":"brdfit-fit-params","format_version":1,"fits":[{"source":"t.h5",)"
         R"("material":"t","model":")" +
         model + R"(","status":"converged","message":"","params":)" + params +
         R"(,"metrics":{"log_rmse":0.1,"cbrt_rmse":0.02,"rel_l2":0.03},)"
         R"("options":{"budget":"full","loss":"log"}})"
         "]}";
}

TEST_F(StrictReaders, FitParametersJsonOfAnUnknownModelOrOutOfBoundsIsRefused) {
  const fs::path good = dir_ / "good.json", model = dir_ / "model.json", huge = dir_ / "huge.json",
                 name = dir_ / "name.json";
  std::ofstream(good) << ParamsJson("lambert", R"({"kd_r":0.5,"kd_g":0.5,"kd_b":0.5})");
  std::ofstream(model) << ParamsJson("lambert+zzz", R"({"kd_r":0.5})");
  std::ofstream(huge) << ParamsJson("lambert", R"({"kd_r":1e300,"kd_g":0.5,"kd_b":0.5})");
  std::ofstream(name) << ParamsJson("lambert", R"({"kd_r":0.5,"kd_g":0.5,"kd_x":0.5})");
  ASSERT_EQ(RunCli(dir_, {"compare", good.string(), good.string()}).code, 0);
  for (const auto& [file, problem] : std::vector<std::pair<fs::path, std::string>>{
           {model, "fits[0].model is 'lambert+zzz', not a registered model"},
           {huge,
            "fits[0].params are not the model's: parameter kd_r = 1e+300 outside the "
            "model's bounds"},
           {name,
            "fits[0].params are not the model's: parameter 2 is 'kd_x', model lambert "
            "calls it 'kd_b'"}}) {
    const CliRun c = RunCli(dir_, {"compare", good.string(), file.string()});
    EXPECT_EQ(c.code, 2) << c.log;
    EXPECT_THAT(c.log, HasSubstr("brdfit: error: " + file.string() + ": " + problem)) << c.log;
  }
}

TEST_F(StrictReaders, ATruncatedPngIsRefusedOrNotedWithKeepGoing) {
  Image img(16, 16);
  for (float& v : img.rgba) v = 0.5f;
  const fs::path png = dir_ / "view.png", html = dir_ / "r.html";
  WritePng(png, img);
  fs::resize_file(png, fs::file_size(png) / 2);
  const CliRun r = RunCli(
      dir_, {"report", good_.string(), png.string(), "--no-renders", "-q", "-o", html.string()});
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + png.string() + ": ")) << r.log;
  EXPECT_FALSE(fs::exists(html));
  const CliRun k = RunCli(dir_, {"report", good_.string(), png.string(), "--keep-going",
                                 "--no-renders", "-q", "-o", html.string()});
  EXPECT_EQ(k.code, 2) << k.log;
  ASSERT_TRUE(fs::exists(html));
  EXPECT_THAT(ReadAll(html), HasSubstr("Left out (unreadable): " + png.string()));
  EXPECT_THAT(ReadAll(html), ::testing::Not(HasSubstr("data:image/png")));
}

TEST(StrictScene, DuplicateKeysAreRefusedNamingTheKey) {
  ScratchDir dir;
  const fs::path scene = dir / "s.json";
  std::ofstream(scene) << R"({"materials": {"m": {"type": "analytic", "model": "lambert",
    "model": "ggx"}}, "objects": [{"shape": "sphere", "material": "m"}]})";
  const CliRun r = RunCli(dir, {"render", scene.string(), "-o", (dir / "x.png").string()});
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + scene.string() +
                               ": duplicate key 'model' in materials.m"))
      << r.log;
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

TEST(StrictTables, AnExternalLinkInValuesIsNotFollowed) {
  ScratchDir dir;
  const fs::path other = dir / "other.h5", linked = dir / "linked.h5";
  WriteHdf5Table(SmallTable(), other);
  WriteHdf5Table(SmallTable(), linked);
  {
    H5::H5File f(linked.string(), H5F_ACC_RDWR);
    f.unlink("values");
    ASSERT_GE(H5Lcreate_external(other.filename().c_str(), "/values", f.getId(), "values",
                                 H5P_DEFAULT, H5P_DEFAULT),
              0);
  }
  try {
    ReadHdf5Table(linked);
    ADD_FAILURE() << "the external link was followed";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(linked.string() + ": /values is an external link"));
  }
  const CliRun r = RunCli(dir, {"info", linked.string()});
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("/values is an external link")) << r.log;
}

TEST(StrictTables, ProvenanceParametersThatAreNotJsonAreRefused) {
  ScratchDir dir;
  const fs::path p = dir / "t.h5";
  WriteHdf5Table(SmallTable(), p);
  {
    H5::H5File f(p.string(), H5F_ACC_RDWR);
    H5::Group prov = f.openGroup("provenance");
    prov.removeAttr("parameters");
    hdf5::WriteStringAttr(prov, "parameters", "{\"kd_r\": 0.5");
  }
  try {
    ReadHdf5Table(p);
    ADD_FAILURE() << "provenance that is not JSON was read";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(p.string() + ": /provenance@parameters is not JSON"));
  }
}

}  // namespace
}  // namespace brdfit
