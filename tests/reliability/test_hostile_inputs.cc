// Hostile inputs and options through the executable (issue 14 items 10-12, 15, 16): each bad
// input or option exits non-zero naming the file and the problem, and writes nothing under an
// output's name. Each test states the item it reproduces.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <H5Cpp.h>
#include <fmt/core.h>
#include <sys/types.h>
#include <zip.h>

#include <nlohmann/json.hpp>

#include "cli_process.h"
#include "tmpfs_mount.h"
#include "core/synth.h"
#include "core/error.h"
#include "io/exr_texture.h"
#include "io/factor_io.h"
#include "io/fit_report.h"
#include "io/hdf5_table.h"
#include "io/hdf5_util.h"
#include "models/registry.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using testing_cli::ReadAll;
using testing_cli::Spawn;
using testing_cli::Wait;

using testing_cli::CliRun;

CliRun RunCli(const ScratchDir& dir, const std::vector<std::string>& args) {
  return testing_cli::Run(args, dir / "run.log");
}

// ---- item 12: synth noise and seed -------------------------------------------------------

TEST(HostileSynth, HugeNoiseIsRefusedAndNothingIsWritten) {
  ScratchDir dir;
  const std::string out = (dir / "t.h5").string();
  for (const char* noise : {"1e308", "11", "inf", "nan", "-1"}) {
    const CliRun r = RunCli(dir, {"synth", "--model", "lambert+ggx", "--grid", "8,8,16", "--noise",
                               noise, "-o", out});
    EXPECT_EQ(r.code, 2) << noise << ": " << r.log;
    EXPECT_THAT(r.log, HasSubstr("--noise")) << noise;
    EXPECT_FALSE(fs::exists(out)) << noise;
  }
  // The largest accepted sigma writes only finite values.
  const CliRun ok = RunCli(dir, {"synth", "--model", "lambert+ggx", "--grid", "8,8,16", "--noise",
                              "10", "--seed", "3", "-o", out});
  ASSERT_EQ(ok.code, 0) << ok.log;
  const Table t = ReadHdf5Table(out);  // the reader refuses a non-finite valid value
  std::size_t valid = 0;
  for (std::size_t i = 0; i < t.valid.size(); ++i) {
    if (!t.valid[i]) continue;
    ++valid;
    for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(t.Value(i)[c])) << i;
  }
  EXPECT_GT(valid, 0u);
}

TEST(HostileSynth, SeedsThatAreNotIntegersInRangeAreRefused) {
  ScratchDir dir;
  const std::string out = (dir / "t.h5").string();
  for (const char* seed : {"-1", "1e20", "18446744073709551616", "7x", "", "0x10"}) {
    const CliRun r = RunCli(dir, {"synth", "--model", "lambert", "--grid", "4,4,8", "--seed", seed,
                               "-o", out});
    EXPECT_EQ(r.code, 2) << "'" << seed << "': " << r.log;
    EXPECT_THAT(r.log, HasSubstr("--seed '" + std::string(seed) +
                                 "': expected an integer in [0, 18446744073709551615]"));
    EXPECT_FALSE(fs::exists(out)) << seed;
  }
  const CliRun max = RunCli(dir, {"synth", "--model", "lambert", "--grid", "4,4,8", "--seed",
                               "18446744073709551615", "-o", out});
  ASSERT_EQ(max.code, 0) << max.log;
  EXPECT_EQ(ReadHdf5Table(out).provenance.seed, 18446744073709551615ull);
}

// ---- items 10 and 11: report and compare on broken inputs ---------------------------------

// A lambert+ggx table on a 16 x 16 x 32 grid (t.h5), its fit report (fits.h5, one lambert+ggx
// fit naming the table) and its factorization (fac/t.{p.exr,q.exr,factor.json}).
class BrokenInputs : public ::testing::Test {
 protected:
  void SetUp() override {
    const ModelInfo* m = FindModel("lambert+ggx");
    params_ = m->DefaultParams();
    const Table t = SynthesizeTable(
        Grid{16, 16, 32, ThetaHMapping::kSqrt},
        [&](const Geometry& g, double rgb[3]) { m->eval(params_.data(), g, rgb); }, {});
    WriteHdf5Table(t, table_);
    FitReportEntry e;
    e.source = table_.string();
    e.material = "t";
    e.options = R"({"budget":"full","loss":"log"})";
    FitResult& r = e.result;
    r.model = m->name;
    r.param_names = m->param_names;
    r.params = params_;
    r.at_bound.assign(r.params.size(), false);
    r.status = FitStatus::kConverged;
    r.metrics.ok = true;
    r.metrics.log_rmse = r.metrics.cbrt_rmse = r.metrics.rel_l2 = 0.01;
    WriteFitReport({e}, fits_);
  }

  void Factor() {
    const CliRun r = RunCli(dir_, {"factor", table_.string(), "--res", "16", "-q", "-o",
                                (dir_ / "fac").string()});
    ASSERT_EQ(r.code, 0) << r.log;
  }

  // `brdfit report ARGS -o r.html` must exit 2 naming `file` and `problem`, writing nothing.
  void ExpectReportRefuses(const std::vector<std::string>& inputs, const std::string& file,
                           const std::string& problem) {
    std::vector<std::string> args = {"report"};
    args.insert(args.end(), inputs.begin(), inputs.end());
    args.insert(args.end(), {"-q", "-o", html_.string()});
    const CliRun r = RunCli(dir_, args);
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + file)) << r.log;
    EXPECT_THAT(r.log, HasSubstr(problem)) << r.log;
    EXPECT_FALSE(fs::exists(html_));
  }

  void ExpectCompareRefuses(const std::string& a, const std::string& b, const std::string& file,
                            const std::string& problem) {
    const CliRun r = RunCli(dir_, {"compare", a, b});
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + file)) << r.log;
    EXPECT_THAT(r.log, HasSubstr(problem)) << r.log;
  }

  std::string P(const std::string& name) const { return (dir_ / name).string(); }

  ScratchDir dir_;
  std::vector<double> params_;
  fs::path table_ = dir_ / "t.h5", fits_ = dir_ / "fits.h5", html_ = dir_ / "r.html";
};

TEST_F(BrokenInputs, ReportOfGoodInputsIsWritten) {  // the baseline of the cases below
  Factor();
  const CliRun r = RunCli(dir_, {"report", fits_.string(), P("fac/t.factor.json"), "-q", "-o",
                              html_.string()});
  ASSERT_EQ(r.code, 0) << r.log;
  EXPECT_TRUE(fs::exists(html_));
}

TEST_F(BrokenInputs, ReportRefusesATruncatedMerlTable) {
  const CliRun s = RunCli(dir_, {"synth", "--model", "lambert", "-o", P("m.binary")});
  ASSERT_EQ(s.code, 0) << s.log;
  fs::resize_file(P("m.binary"), 1000000);
  ExpectReportRefuses({P("m.binary")}, P("m.binary"), "expected 34992012");
}

TEST_F(BrokenInputs, ReportRefusesHdf5TablesWithoutValuesOrWithNaN) {
  fs::copy_file(table_, P("novalues.h5"));
  H5::H5File(P("novalues.h5"), H5F_ACC_RDWR).unlink("values");
  ExpectReportRefuses({P("novalues.h5")}, P("novalues.h5"), "missing dataset /values");
  // The fit report names the table: a damaged table it names is an error too.
  Table t = ReadHdf5Table(table_);
  std::size_t i = 0;
  while (!t.valid[i]) ++i;
  t.Value(i)[0] = std::nan("");
  WriteHdf5Table(t, table_);
  ExpectReportRefuses({fits_.string()}, table_.string(), "NaN at valid cell");
}

TEST_F(BrokenInputs, ReportRefusesAFitReportWhoseFormatSaysTable) {
  {
    H5::H5File f(fits_.string(), H5F_ACC_RDWR);
    f.removeAttr("format");
    hdf5::WriteStringAttr(f, "format", kHdf5TableFormat);
  }
  ExpectReportRefuses({fits_.string()}, fits_.string(), "missing dataset /values");
}

TEST_F(BrokenInputs, ReportRefusesSidecarsOfANewerVersionOrWithBrokenTextures) {
  Factor();
  const fs::path sidecar = dir_ / "fac/t.factor.json", p = dir_ / "fac/t.p.exr";
  const std::string good_sidecar = ReadAll(sidecar), good_p = ReadAll(p);
  auto restore = [&] {
    std::ofstream(sidecar, std::ios::binary) << good_sidecar;
    std::ofstream(p, std::ios::binary) << good_p;
  };
  nlohmann::json j = nlohmann::json::parse(good_sidecar);
  j["format_version"] = kFactorFormatVersion + 1;
  std::ofstream(sidecar, std::ios::binary) << j.dump();
  ExpectReportRefuses({sidecar.string()}, sidecar.string(),
                      fmt::format("unsupported format_version {} (this reader: {} to {})",
                                  kFactorFormatVersion + 1, kFactorFormatOldestVersion,
                                  kFactorFormatVersion));
  restore();
  fs::remove(p);
  ExpectReportRefuses({sidecar.string()}, p.string(), "");
  restore();
  fs::resize_file(p, good_p.size() / 2);
  ExpectReportRefuses({sidecar.string()}, p.string(), "");
  restore();
  std::ofstream(p, std::ios::binary) << std::string(4000, '\x7f') << "garbage";
  ExpectReportRefuses({sidecar.string()}, p.string(), "");
  restore();
  // An EXR of another size (a 8 x 8 factorization's p) under the sidecar's name.
  const CliRun r8 = RunCli(dir_, {"factor", table_.string(), "--res", "8", "-q", "-o", P("fac8")});
  ASSERT_EQ(r8.code, 0) << r8.log;
  fs::copy_file(dir_ / "fac8/t.p.exr", p, fs::copy_options::overwrite_existing);
  ExpectReportRefuses({sidecar.string()}, p.string(), "image is 8 x 8, the sidecar t.factor.json says 16 x 16");
}

TEST_F(BrokenInputs, ReportKeepGoingWritesThePageNotesTheProblemAndExitsTwo) {
  fs::copy_file(table_, P("novalues.h5"));
  H5::H5File(P("novalues.h5"), H5F_ACC_RDWR).unlink("values");
  std::ofstream(P("x.factor.json")) << "{";
  const CliRun r = RunCli(dir_, {"report", fits_.string(), P("novalues.h5"), P("x.factor.json"),
                              "--keep-going", "--no-renders", "-q", "-o", html_.string()});
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + P("novalues.h5") + ": missing dataset /values"));
  EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + P("x.factor.json") + ": not a JSON object"));
  EXPECT_THAT(r.log, HasSubstr("2 problems noted in " + html_.string()));
  ASSERT_TRUE(fs::exists(html_));
  const std::string html = ReadAll(html_);
  EXPECT_THAT(html, HasSubstr("Left out (unreadable): " + P("x.factor.json")));
  EXPECT_THAT(html, HasSubstr("No θh slices: " + P("novalues.h5") + ": missing dataset /values"));
  EXPECT_THAT(html, HasSubstr("t: θd = "));  // the good material still has its slices
}

// A fit parameters file (brdfit fit --json) with one lambert+ggx fit.
std::string ParamsJson(const std::string& log_rmse) {
  return R"({"format":"brdfit-fit-params","format_version":1,"fits":[{"source":"t.h5",)"
         R"("material":"t","model":"lambert+ggx","status":"converged","message":"",)"
         R"("params":{"lambert.kd_r":0.3,"lambert.kd_g":0.3,"lambert.kd_b":0.3,"ggx.ks_r":0.5,)"
         R"("ggx.ks_g":0.5,"ggx.ks_b":0.5,"ggx.alpha":0.2},"metrics":{"log_rmse":)" +
         log_rmse + R"(,"cbrt_rmse":0.02,"rel_l2":0.03},"options":{"budget":"full","loss":"log"}}]})";
}

TEST_F(BrokenInputs, CompareRefusesANullOrNegativeMetric) {
  std::ofstream(P("old.json")) << ParamsJson("0.1");
  std::ofstream(P("null.json")) << ParamsJson("null");
  std::ofstream(P("neg.json")) << ParamsJson("-0.5");
  std::ofstream(P("text.json")) << ParamsJson("\"0.01\"");
  const CliRun same = RunCli(dir_, {"compare", P("old.json"), P("old.json")});
  EXPECT_EQ(same.code, 0) << same.log;
  ExpectCompareRefuses(P("old.json"), P("null.json"), P("null.json"),
                       "fits[0].metrics.log_rmse is null, not a number");
  ExpectCompareRefuses(P("old.json"), P("neg.json"), P("neg.json"),
                       "fits[0].metrics.log_rmse is -0.5, below 0");
  ExpectCompareRefuses(P("text.json"), P("old.json"), P("text.json"),
                       "fits[0].metrics.log_rmse is string, not a number");
}

TEST_F(BrokenInputs, CompareRefusesASidecarWithOnlyFormatFields) {
  Factor();
  std::ofstream(P("bare.factor.json")) << R"({"format":"brdfit-factorization","format_version":1})";
  ExpectCompareRefuses(P("fac/t.factor.json"), P("bare.factor.json"), P("bare.factor.json"),
                       "missing");
}

TEST_F(BrokenInputs, CompareRefusesNaNInABenchCsv) {
  const std::string header = "material,model,budget,time_ms,log_rmse,metric_ok\n";
  std::ofstream(P("old.csv")) << header << "t,lambert+ggx,full,10,0.1,1\n";
  std::ofstream(P("nan.csv")) << header << "t,lambert+ggx,full,10,nan,1\n";
  std::ofstream(P("empty.csv")) << header << "t,lambert+ggx,full,10,,1\n";
  std::ofstream(P("negtime.csv")) << header << "t,lambert+ggx,full,-3,0.1,1\n";
  EXPECT_EQ(RunCli(dir_, {"compare", P("old.csv"), P("old.csv")}).code, 0);
  ExpectCompareRefuses(P("old.csv"), P("nan.csv"), P("nan.csv"),
                       "line 2: column log_rmse: 'nan' is not finite");
  ExpectCompareRefuses(P("old.csv"), P("empty.csv"), P("empty.csv"),
                       "line 2: column log_rmse is empty");
  ExpectCompareRefuses(P("old.csv"), P("negtime.csv"), P("negtime.csv"),
                       "line 2: column time_ms: -3 is negative");
}

TEST_F(BrokenInputs, AFifoOrADeviceIsNotARegularFileNotAMissingOne) {
  const std::string header = "material,model,budget,time_ms,log_rmse,metric_ok\n";
  std::ofstream(P("old.csv")) << header << "t,lambert+ggx,full,10,0.1,1\n";
  ASSERT_EQ(mkfifo(P("fifo.csv").c_str(), 0644), 0);
  ExpectCompareRefuses(P("old.csv"), P("fifo.csv"), P("fifo.csv"),
                       "is a FIFO, not a regular file");
  ExpectCompareRefuses("/dev/zero", P("old.csv"), "/dev/zero",
                       "is a character device, not a regular file");
  ExpectReportRefuses({P("fifo.csv")}, P("fifo.csv"), "is a FIFO, not a regular file");
  ExpectCompareRefuses(P("old.csv"), P("gone.csv"), P("gone.csv"), "no such file or folder");
}

// ---- item 15: output errors of factor, fit on a missing input ----------------------------

// Names of the files in `dir` (not recursive).
std::vector<std::string> Files(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST_F(BrokenInputs, FactorIntoAReadOnlyOrFullFolderIsAnOutputErrorExitTwo) {
  for (const bool read_only : {true, false}) {
    SCOPED_TRACE(read_only ? "read-only" : "full");
    // Read-only: an empty tmpfs mounted read-only. Full: 16 kB, less than one 64 x 64 EXR.
    testing_cli::TmpfsMount disk(dir_ / "disk", 16, read_only);
    if (!disk.mounted()) GTEST_SKIP() << disk.why();
    const CliRun r = RunCli(dir_, {"factor", table_.string(), "--res", "64", "-q", "-o",
                                disk.path().string()});
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + (disk.path() / "t.").string())) << r.log;
    EXPECT_THAT(r.log, Not(HasSubstr("solve"))) << r.log;
    // No temporary left, and no sidecar: a final name only ever holds a complete file.
    for (const std::string& f : Files(disk.path())) {
      EXPECT_EQ(f.find(".tmp-"), std::string::npos) << f;
      EXPECT_NE(f, "t.factor.json");
    }
  }
}

TEST_F(BrokenInputs, AnOutputFolderThatCannotBeCreatedIsNamed) {
  testing_cli::TmpfsMount disk(dir_ / "ro", 16, /*read_only=*/true);
  if (!disk.mounted()) GTEST_SKIP() << disk.why();
  const fs::path out = disk.path() / "sub" / "dir";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"factor", table_.string(), "--res", "8", "-q", "-o", out.string()},
        {"demo", "-o", out.string()}}) {
    const CliRun r = RunCli(dir_, args);
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + out.string() +
                                 ": cannot create the folder: Read-only file system"));
    EXPECT_THAT(r.log, Not(HasSubstr("filesystem error")));
  }
}

TEST(HostileFit, AMissingInputExitsTwoAndWritesNoReport) {
  ScratchDir dir;
  const CliRun r = RunCli(dir, {"fit", (dir / "none.binary").string(), "--model", "lambert", "-o",
                             (dir / "fits.h5").string(), "--json", (dir / "fits.json").string()});
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + (dir / "none.binary").string() + ": no such file"));
  EXPECT_EQ(Files(dir.path()), std::vector<std::string>{"run.log"});
  // A damaged input: exit 2, no report either (nothing was fitted).
  std::ofstream(dir / "bad.binary") << "not a table";
  const CliRun d = RunCli(dir, {"fit", (dir / "bad.binary").string(), "--model", "lambert", "-o",
                             (dir / "fits.h5").string()});
  EXPECT_EQ(d.code, 2) << d.log;
  EXPECT_FALSE(fs::exists(dir / "fits.h5"));
}

// ---- item 4: a full disk ---------------------------------------------------------------

TEST_F(BrokenInputs, FitOntoAFullDiskExitsTwoAndLeavesNoDamagedOrTemporaryFile) {
  testing_cli::TmpfsMount disk(dir_ / "disk", 8);  // less than a report of two fits
  if (!disk.mounted()) GTEST_SKIP() << disk.why();
  const fs::path report = disk.path() / "fits.h5";
  const CliRun r = RunCli(dir_, {"fit", table_.string(), "--model", "lambert,lambert+ggx",
                                 "--budget", "stride:4", "--no-progress", "-q", "-o",
                                 report.string(), "--json", (disk.path() / "fits.json").string()});
  EXPECT_EQ(r.code, 2) << r.log;  // was a SIGSEGV (139) after "H5Fclose failed"
  EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + report.string() +
                               ": write failed: No space left on device"));
  EXPECT_THAT(r.log, Not(HasSubstr("HDF5")));
  EXPECT_EQ(Files(disk.path()), std::vector<std::string>{});  // no report, temporary or lock
  // synth's HDF5 table and report's HTML: the same.
  const CliRun t = RunCli(dir_, {"synth", "--model", "lambert", "--grid", "16,16,32", "-o",
                                 (disk.path() / "t.h5").string()});
  EXPECT_EQ(t.code, 2) << t.log;
  EXPECT_THAT(t.log, HasSubstr((disk.path() / "t.h5").string() + ": write failed"));
  const CliRun h = RunCli(dir_, {"report", fits_.string(), "-q", "-o",
                                 (disk.path() / "r.html").string()});
  EXPECT_EQ(h.code, 2) << h.log;
  EXPECT_THAT(h.log, HasSubstr((disk.path() / "r.html").string() + ": write failed"));
  EXPECT_EQ(Files(disk.path()), std::vector<std::string>{});
}

TEST_F(BrokenInputs, AFullDiskLeavesThePreviousReportAsItWas) {
  testing_cli::TmpfsMount disk(dir_ / "disk", 32);  // one report, not it and a bigger one
  if (!disk.mounted()) GTEST_SKIP() << disk.why();
  const fs::path report = disk.path() / "fits.h5";
  const std::vector<std::string> common = {"--budget", "stride:4", "--no-progress", "-q", "-o",
                                           report.string()};
  std::vector<std::string> first = {"fit", table_.string(), "--model", "lambert"};
  first.insert(first.end(), common.begin(), common.end());
  const CliRun one = RunCli(dir_, first);
  ASSERT_EQ(one.code, 0) << one.log;
  const std::string before = ReadAll(report);
  std::vector<std::string> more = {"fit", table_.string(), "--model",
                                   "lambert,lambert+ggx,lambert+beckmann"};
  more.insert(more.end(), common.begin(), common.end());
  const CliRun r = RunCli(dir_, more);
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr(report.string() + ": write failed: No space left on device"));
  EXPECT_EQ(ReadAll(report), before);
  EXPECT_EQ(ReadFitReport(report).size(), 1u);
  EXPECT_EQ(Files(disk.path()), std::vector<std::string>{"fits.h5"});
}

// ---- item 16: messages ----------------------------------------------------------------

// Every character of a message is printable (or a line break): no raw bytes of a file.
void ExpectPrintable(const std::string& log) {
  for (const char c : log) {
    const auto u = static_cast<unsigned char>(c);
    // UTF-8 of brdfit's own messages (θ, ×) is fine; control characters are not.
    ASSERT_TRUE(u == '\n' || u >= 0x20) << "byte " << int(u) << " in: " << log;
    ASSERT_NE(u, 0x7f) << log;
  }
}

TEST_F(BrokenInputs, AGarbageExrIsNamedWithoutItsRawBytes) {
  Factor();
  std::string garbage = "v/1\x01\x02";  // OpenEXR's magic and version, then noise
  garbage.append(3, '\0');
  for (int k = 0; k < 40; ++k) {
    for (int b = 0; b < 256; ++b) garbage += static_cast<char>(b);
  }
  std::ofstream(dir_ / "fac/t.p.exr", std::ios::binary) << garbage;
  const CliRun r = RunCli(dir_, {"report", P("fac/t.factor.json"), "-q", "-o", html_.string()});
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + P("fac/t.p.exr") + ": "));
  ExpectPrintable(r.log);
  EXPECT_LT(r.log.size(), 600u) << r.log;
}

// The reader's message itself: a damaged header quotes the attribute name it found, which is
// whatever bytes the file holds there.
TEST(HostileMessages, AGarbageExrMessageHasNoRawBytes) {
  ScratchDir dir;
  std::string header = "v/1\x01\x02";
  header.append(3, '\0');
  header += "\x1b[31m\x07\xff garbage" + std::string(1, '\0') + "int" + std::string(1, '\0');
  header += std::string("\xff\xff\xff\x7f", 4);  // declares 2 GB
  header += std::string(64, '\x9b');
  std::ofstream(dir / "g.exr", std::ios::binary) << header;
  try {
    ReadRgbExr(dir / "g.exr");
    FAIL() << "read";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind((dir / "g.exr").string() + ": damaged OpenEXR header: attribute '", 0),
              0u)
        << msg;
    EXPECT_THAT(msg, HasSubstr("\\x1b[31m\\x07\\xff garbage"));
    ExpectPrintable(msg);
  }
}

TEST(HostileMessages, UsageErrorsHaveTheBrdfitPrefixAndNoHugeNumbers) {
  ScratchDir dir;
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"fit", "--jobs", "x", "t.h5"}, {}, {"report"},
        {"render", "--frames", "-1", "scene.json"}}) {
    const CliRun r = RunCli(dir, args);
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_EQ(r.log.rfind("brdfit: error: ", 0), 0u) << r.log;
    EXPECT_LT(r.log.size(), 200u) << r.log;  // --frames -1 printed a 300-digit bound
  }
  const CliRun frames = RunCli(dir, {"render", "--frames", "-1", "scene.json"});
  EXPECT_THAT(frames.log, HasSubstr("--frames: Value -1 not in range 0 to 2147483647"));
  EXPECT_EQ(RunCli(dir, {"--help"}).code, 0);
}

TEST(HostileMessages, ASceneThatIsAFolderIsNamedAsOne) {
  ScratchDir dir;
  fs::create_directories(dir / "scene.json");
  const CliRun r = RunCli(dir, {"render", (dir / "scene.json").string(), "-o",
                                (dir / "x.png").string()});
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr((dir / "scene.json").string() + ": is a directory"));
  EXPECT_THAT(r.log, Not(HasSubstr("JSON")));
}

// A zip archive of `members` (name -> bytes).
void WriteZip(const fs::path& path, const std::vector<std::pair<std::string, std::string>>& members) {
  int err = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  ASSERT_NE(z, nullptr);
  for (const auto& [name, bytes] : members) {
    zip_source_t* src = zip_source_buffer(z, bytes.data(), bytes.size(), 0);
    ASSERT_GE(zip_file_add(z, name.c_str(), src, ZIP_FL_OVERWRITE), 0);
  }
  ASSERT_EQ(zip_close(z), 0);  // copies the buffers, which outlive it
}

TEST(HostileMessages, ArchivesWithoutNetworksOrWithoutMaterialsSaySo) {
  ScratchDir dir;
  WriteHdf5Table(Table::Empty(Grid{2, 2, 4, ThetaHMapping::kLinear}), dir / "table.h5");
  const std::string table = ReadAll(dir / "table.h5");
  WriteZip(dir / "nonet.zip", {{"merl_nbrdf/x.h5", table}});
  WriteZip(dir / "empty.zip", {{"readme.txt", "no networks here"}});
  const std::string out = (dir / "t.h5").string();
  const CliRun member = RunCli(dir, {"synth", "--nbrdf", "x", "--nbrdf-zip",
                                     (dir / "nonet.zip").string(), "-o", out});
  EXPECT_EQ(member.code, 2) << member.log;
  EXPECT_THAT(member.log, HasSubstr("merl_nbrdf/x.h5: not an NBRDF network"));
  EXPECT_THAT(member.log, Not(HasSubstr("H5Lexists")));
  const CliRun list =
      RunCli(dir, {"synth", "--list-nbrdf", "--nbrdf-zip", (dir / "empty.zip").string()});
  EXPECT_EQ(list.code, 2) << list.log;
  EXPECT_THAT(list.log, HasSubstr("empty.zip: holds no NBRDF materials"));
  setenv("BRDFIT_NBRDF_ZIP", (dir / "empty.zip").c_str(), 1);
  const CliRun all = RunCli(dir, {"fit", "nbrdf:all", "--model", "lambert", "-o",
                                  (dir / "f.h5").string()});
  unsetenv("BRDFIT_NBRDF_ZIP");
  EXPECT_EQ(all.code, 2) << all.log;
  EXPECT_THAT(all.log, HasSubstr("empty.zip: holds no NBRDF materials"));
  EXPECT_FALSE(fs::exists(dir / "f.h5"));
}

// A 32 x 32 scene of one lambert sphere under n directional lights.
void WriteLightsScene(const fs::path& path, int n) {
  nlohmann::json lights = nlohmann::json::array();
  for (int i = 0; i < n; ++i) {
    lights.push_back({{"name", "l" + std::to_string(i)}, {"type", "directional"},
                      {"direction", {1, 1, 1}}});
  }
  const nlohmann::json scene = {
      {"image", {{"width", 32}, {"height", 32}}},
      {"lights", lights},
      {"materials", {{"m", {{"type", "analytic"}, {"model", "lambert"}}}}},
      {"objects", {{{"name", "ball"}, {"shape", "sphere"}, {"centre", {0, 0, 0}}, {"radius", 1},
                    {"material", "m"}}}}};
  std::ofstream(path) << scene.dump();
}

TEST(HostileMessages, MoreLightsThanTheShaderHoldsAreRefusedWithTheLimit) {
  ScratchDir dir;
  WriteLightsScene(dir / "one.json", 1);
  const CliRun one = RunCli(dir, {"render", (dir / "one.json").string(), "-o",
                                  (dir / "one.png").string()});
  if (one.code != 0) GTEST_SKIP() << "no headless OpenGL here: " << one.log;
  WriteLightsScene(dir / "many.json", 5000);
  const CliRun r = RunCli(dir, {"render", (dir / "many.json").string(), "-o",
                                (dir / "many.png").string()});
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("object 'ball': 5000 lights reach it"));
  EXPECT_THAT(r.log, HasSubstr("GL_MAX_FRAGMENT_UNIFORM_COMPONENTS"));
  EXPECT_FALSE(fs::exists(dir / "many.png"));
}

}  // namespace
}  // namespace brdfit
