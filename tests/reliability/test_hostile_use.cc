// Reliability under hostile use (issue 14), through the executable: the output policy of every
// command (no output that is an input or another output, no FIFO/device/folder), names from
// inside archives kept inside -o, signals (temporaries removed, the report kept, a rerun
// resumes), two writers of one report. Each test states the item of issue 14 it reproduces.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <zip.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "cli_process.h"
#include "core/file_stem.h"
#include "core/synth.h"
#include "io/fit_report.h"
#include "io/hdf5_table.h"
#include "models/registry.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using ::testing::HasSubstr;
using testing_cli::ReadAll;
using testing_cli::Spawn;
using testing_cli::SpawnHeld;
using testing_cli::WaitForFile;
using testing_cli::Wait;

using testing_cli::CliRun;

// Runs brdfit to completion with its output in `log`.
CliRun RunBrdfit(const std::vector<std::string>& args, const fs::path& log) {
  return testing_cli::Run(args, log);
}

// n synthetic lambert+ggx tables (varied roughness) on a g^2 x 2g grid.
std::vector<std::string> MakeTables(const fs::path& dir, int n, int g = 16) {
  Grid grid;
  grid.n_theta_h = g;
  grid.n_theta_d = g;
  grid.n_phi_d = 2 * g;
  const ModelInfo* m = FindModel("lambert+ggx");
  std::vector<std::string> files;
  fs::create_directories(dir);
  for (int i = 0; i < n; ++i) {
    const double kd = 0.2 + 0.05 * (i % 7), alpha = 0.05 + 0.04 * (i % 9);
    const std::vector<double> p = {kd, 0.8 * kd, 0.6 * kd, 0.4, 0.4, 0.4, alpha};
    SynthOptions so;
    so.noise = 0.05;
    so.seed = static_cast<std::uint64_t>(i + 1);
    const Table t = SynthesizeTable(
        grid, [&](const Geometry& geo, double rgb[3]) { m->eval(p.data(), geo, rgb); }, so);
    std::string name = "t";
    name += std::to_string(i);
    name += ".h5";
    WriteHdf5Table(t, dir / name);
    files.push_back((dir / name).string());
  }
  return files;
}

// Every file under `dir` (recursively) with its bytes, for "nothing written / changed".
std::map<std::string, std::string> Snapshot(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "run.log") continue;
    if (e.is_symlink() || !e.is_regular_file()) {
      out[e.path().string()] = "<not a regular file>";
    } else {
      out[e.path().string()] = ReadAll(e.path());
    }
  }
  return out;
}

// ---- item 1: names from inside files -----------------------------------------------------

TEST(SafeFileStem, KeepsSafeNamesAndMakesOthersOneComponent) {
  EXPECT_EQ(SafeFileStem("gold-metallic-paint"), "gold-metallic-paint");
  EXPECT_EQ(SafeFileStem("t0.mccool"), "t0.mccool");
  EXPECT_EQ(SafeFileStem(""), "unnamed");
  EXPECT_EQ(SafeFileStem("."), "unnamed");
  EXPECT_EQ(SafeFileStem(".hidden"), "hidden");
  EXPECT_EQ(SafeFileStem("a/b"), "a_b");
  EXPECT_EQ(SafeFileStem(std::string("a\0b\n", 4)), "a_b_");
  EXPECT_EQ(SafeFileStem(std::string(300, 'x')), std::string(kMaxFileStem, 'x'));
  for (const std::string hostile : {"../../X", "/abs/X", "..", "...", "a/../../b", "x\\..\\y"}) {
    const std::string s = SafeFileStem(hostile);
    EXPECT_EQ(s.find('/'), std::string::npos) << hostile << " -> " << s;
    EXPECT_EQ(s.find(".."), std::string::npos) << hostile << " -> " << s;
    EXPECT_NE(s.front(), '.') << hostile << " -> " << s;
    EXPECT_EQ(fs::path(s).filename().string(), s) << hostile << " -> " << s;
  }
}

// An NBRDF network's bytes, taken from the shared archive (skips without it).
std::string SomeNbrdfMember() {
  const fs::path zip = fs::path(BRDFIT_SHARED_DATA) / "merl_nbrdf.zip";
  int err = 0;
  zip_t* z = zip_open(zip.c_str(), ZIP_RDONLY, &err);
  if (!z) return "";
  std::string bytes;
  for (zip_int64_t i = 0; i < zip_get_num_entries(z, 0) && bytes.empty(); ++i) {
    const std::string name = zip_get_name(z, static_cast<zip_uint64_t>(i), 0);
    if (!name.ends_with(".h5")) continue;
    zip_stat_t st;
    zip_stat_index(z, static_cast<zip_uint64_t>(i), 0, &st);
    bytes.resize(st.size);
    zip_file_t* f = zip_fopen_index(z, static_cast<zip_uint64_t>(i), 0);
    zip_fread(f, bytes.data(), st.size);
    zip_fclose(f);
  }
  zip_discard(z);
  return bytes;
}

void WriteZip(const fs::path& path, const std::vector<std::string>& names,
              const std::string& data) {
  int err = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  ASSERT_NE(z, nullptr);
  for (const std::string& name : names) {
    zip_source_t* src = zip_source_buffer(z, data.data(), data.size(), 0);
    ASSERT_GE(zip_file_add(z, name.c_str(), src, ZIP_FL_OVERWRITE), 0) << name;
  }
  ASSERT_EQ(zip_close(z), 0);
}

// Issue 14 item 1: members "merl_nbrdf/../../X.h5" and "merl_nbrdf//<abs>/X.h5" made
// `factor nbrdf:all -o a/b/out` write two folders above -o and at the absolute path.
TEST(HostileNames, FactorOfArchiveMembersWritesOnlyInsideTheOutputFolder) {
  const std::string member = SomeNbrdfMember();
  if (member.empty()) GTEST_SKIP() << "no " << BRDFIT_SHARED_DATA << "/merl_nbrdf.zip";
  ScratchDir dir;
  const fs::path abs = dir / "abs";
  const fs::path zip = dir / "hostile.zip";
  // The second member is "merl_nbrdf//<abs>/X.h5": its material name is the absolute "/<abs>/X".
  WriteZip(zip, {"merl_nbrdf/../../X.h5", "merl_nbrdf/" + (abs / "X.h5").string()}, member);
  fs::create_directories(dir / "a" / "b");
  ::setenv("BRDFIT_NBRDF_ZIP", zip.c_str(), 1);
  const CliRun r = RunBrdfit({"factor", "nbrdf:all", "--res", "8", "--no-auto", "-o",
                           (dir / "a" / "b" / "out").string()},
                          dir / "run.log");
  ::unsetenv("BRDFIT_NBRDF_ZIP");
  EXPECT_EQ(r.code, 0) << r.log;
  int inside = 0, sidecars = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir.path())) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), dir.path());
    if (rel == "hostile.zip" || rel == "run.log") continue;
    EXPECT_TRUE(rel.string().starts_with("a/b/out/")) << "written outside -o: " << rel;
    inside += rel.string().starts_with("a/b/out/");
    sidecars += rel.string().ends_with(".factor.json");
  }
  // Two materials: a sidecar and at least its p and q each (the chosen form may have more terms).
  EXPECT_EQ(sidecars, 2) << r.log;
  EXPECT_GE(inside, 6) << r.log;
  EXPECT_FALSE(fs::exists(abs)) << r.log;
  EXPECT_FALSE(fs::exists(dir / "X.p.exr"));
}

// ---- items 2 and 3: the output policy ----------------------------------------------------

class OutputPolicy : public ::testing::Test {
 protected:
  void SetUp() override {
    table_ = MakeTables(dir_.path(), 1, 8).front();
    report_ = (dir_ / "fits.h5").string();
    const CliRun r = RunBrdfit({"fit", table_, "--model", "ggx", "-q", "-o", report_},
                            dir_ / "run.log");
    ASSERT_EQ(r.code, 0) << r.log;
  }

  // `brdfit args` refuses with exit 2, names `file` and the problem, and changes nothing.
  void ExpectRefused(const std::vector<std::string>& args, const std::string& file,
                     const std::string& problem) {
    const auto before = Snapshot(dir_.path());
    const CliRun r = RunBrdfit(args, dir_ / "run.log");
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + file + ": ")) << r.log;
    EXPECT_THAT(r.log, HasSubstr(problem)) << r.log;
    EXPECT_TRUE(Snapshot(dir_.path()) == before) << "a refused run changed files: " << r.log;
  }

  ScratchDir dir_;
  std::string table_, report_;
};

TEST_F(OutputPolicy, AnOutputThatIsAnInputIsRefused) {  // item 2
  ExpectRefused({"fit", table_, "--model", "ggx", "-q", "-o", report_, "--json", table_}, table_,
                "--json is also an input of this run");
  ExpectRefused({"fit", table_, "--model", "ggx", "-q", "--force", "-o", table_}, table_,
                "-o is also an input of this run");
  ExpectRefused({"report", report_, "-q", "-o", report_}, report_, "-o is also an input");
  ExpectRefused({"bench", table_, "--models", "ggx", "-q", "-o", table_}, table_,
                "-o is also an input");
  const std::string csv = (dir_ / "b.csv").string();
  ExpectRefused({"bench", table_, "--models", "ggx", "-q", "-o", csv, "--plot", table_}, table_,
                "--plot is also an input");
  ExpectRefused({"render", table_, "-o", table_}, table_, "-o is also an input");
  // Through a symbolic link and a hard link: the same file.
  fs::create_symlink(table_, dir_ / "link.h5");
  fs::create_hard_link(table_, dir_ / "hard.h5");
  for (const char* name : {"link.h5", "hard.h5"}) {
    const std::string out = (dir_ / name).string();
    ExpectRefused({"fit", table_, "--model", "ggx", "-q", "--force", "-o", out}, out,
                  "-o is also an input");
  }
  // factor -o DIR: the outputs inside DIR may not be inputs.
  fs::create_directories(dir_ / "out");
  fs::create_symlink(table_, dir_ / "out" / "t0.p.exr");
  ExpectRefused({"factor", table_, "--res", "8", "-q", "-o", (dir_ / "out").string()},
                (dir_ / "out" / "t0.p.exr").string(), "is also an input");
}

TEST_F(OutputPolicy, TwoOutputsOfOneRunMayNotBeTheSameFile) {  // item 2
  const std::string f = (dir_ / "f.h5").string(), x = (dir_ / "x.csv").string();
  ExpectRefused({"fit", table_, "--model", "ggx", "-q", "-o", f, "--json", f}, f,
                "--json is the same file as -o");
  ExpectRefused({"bench", table_, "--models", "ggx", "-q", "-o", x, "--plot", x}, x,
                "--plot is the same file as -o");
  // Not existing yet: compared by their canonical paths.
  const std::string g = (dir_ / "sub" / ".." / "f.h5").string();
  fs::create_directories(dir_ / "sub");
  ExpectRefused({"fit", table_, "--model", "ggx", "-q", "-o", f, "--json", g}, g,
                "the same file as -o");
}

TEST_F(OutputPolicy, FifosDevicesAndFoldersAreNotOutputs) {  // item 3
  const fs::path fifo = dir_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  ExpectRefused({"fit", table_, "--model", "ggx", "-q", "-o", (dir_ / "f.h5").string(), "--json",
                 fifo.string()},
                fifo.string(), "is a FIFO");
  ExpectRefused({"report", report_, "-q", "-o", fifo.string()}, fifo.string(), "is a FIFO");
  fs::create_directories(dir_ / "folder");
  ExpectRefused({"synth", "--model", "ggx", "--grid", "4,4,8", "-o", (dir_ / "folder").string()},
                (dir_ / "folder").string(), "is a folder");
  ExpectRefused({"demo", "--quick", "-o", report_}, report_, "must be a folder");
  // A device node: /dev/null keeps being one (as root, it used to be replaced by a file).
  const CliRun r = RunBrdfit({"fit", table_, "--model", "ggx", "-q", "-o",
                           (dir_ / "f.h5").string(), "--json", "/dev/null"},
                          dir_ / "run.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("/dev/null: --json is a device node")) << r.log;
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/null is no longer a device";
  // Standard output stays an output.
  const CliRun out = RunBrdfit({"fit", table_, "--model", "ggx", "-q", "-o", report_, "--json", "-"},
                            dir_ / "run.log");
  EXPECT_EQ(out.code, 0) << out.log;
  EXPECT_THAT(out.log, HasSubstr("\"fits\"")) << out.log;
}

// ---- item 13: standard output ----------------------------------------------------------

TEST(StandardOutput, AFailedWriteToStandardOutputIsAnError) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  ScratchDir dir;
  const std::string err = (dir / "err").string();
  for (const std::string args : {"models", "models --json"}) {
    const int status =
        std::system((std::string(BRDFIT_EXE) + " " + args + " >/dev/full 2>" + err).c_str());
    EXPECT_EQ(WEXITSTATUS(status), 2) << args;
    EXPECT_THAT(ReadAll(err), HasSubstr("brdfit: error: ")) << args;
    EXPECT_THAT(ReadAll(err), HasSubstr("No space left on device")) << args;
  }
}

// ---- item 7: signals -----------------------------------------------------------------------

std::vector<std::string> FitArgs(const std::vector<std::string>& tables, const fs::path& out) {
  std::vector<std::string> a = {"fit"};
  a.insert(a.end(), tables.begin(), tables.end());
  for (const char* s : {"--model", "ggx,ward", "--no-timings"}) a.push_back(s);
  a.insert(a.end(), {"-o", out.string()});
  return a;
}

// Files beside the report other than the report itself.
std::vector<std::string> Leftovers(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name != "fits.h5" && !name.ends_with(".log")) out.push_back(name);
  }
  return out;
}

// A pid that is certainly not running: a child that has exited and been reaped.
pid_t DeadPid() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  waitpid(pid, nullptr, 0);
  return pid;
}

TEST(Signals, SigtermKeepsTheReportRemovesTemporariesAndTheRerunResumes) {
  ScratchDir dir;
  const std::vector<std::string> tables = MakeTables(dir / "tables", 12, 32);
  const fs::path run = dir / "run", report = run / "fits.h5";
  fs::create_directories(run);
  // SIGTERM while the batch holds after the checkpoint of its 7th fit (pipeline/batch_hold.h).
  constexpr std::size_t kAfterFits = 7;
  const fs::path hold = dir / "held";
  const pid_t pid = SpawnHeld(FitArgs(tables, report), dir / "fit.log", hold, kAfterFits);
  ASSERT_TRUE(WaitForFile(hold, pid)) << ReadAll(dir / "fit.log");
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  EXPECT_EQ(Wait(pid), 143);
  const std::string log = ReadAll(dir / "fit.log");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(log, m, std::regex(R"(interrupted: (\d+) fits kept, rerun to resume)")))
      << log;
  const std::size_t kept = ReadFitReport(report).size();  // a complete report
  EXPECT_EQ(std::stoul(m[1]), kept) << log;
  EXPECT_EQ(kept, kAfterFits) << log;
  EXPECT_THAT(Leftovers(run), ::testing::IsEmpty()) << "temporaries or a lock left";

  // A dead process's temporary beside the report goes with the rerun; a live one's stays.
  const std::string stale = ".fits.h5.tmp-" + std::to_string(DeadPid()) + "-0";
  const std::string live = ".fits.h5.tmp-" + std::to_string(::getpid()) + "-0";
  std::ofstream(run / stale) << "partial";
  std::ofstream(run / live) << "partial";
  const CliRun rerun = RunBrdfit(FitArgs(tables, report), dir / "rerun.log");
  EXPECT_EQ(rerun.code, 0) << rerun.log;
  ASSERT_TRUE(std::regex_search(rerun.log, m, std::regex(R"((\d+) fits, (\d+) skipped)")))
      << rerun.log;
  EXPECT_EQ(std::stoul(m[2]), kept) << rerun.log;
  EXPECT_EQ(std::stoul(m[1]) + kept, 2 * tables.size()) << rerun.log;
  EXPECT_EQ(ReadFitReport(report).size(), 2 * tables.size());
  EXPECT_FALSE(fs::exists(run / stale)) << "stale temporary of a dead process kept";
  EXPECT_TRUE(fs::exists(run / live)) << "a live process's temporary was removed";
}

TEST(Signals, SigintAndSighupExitWith130And129AndLeaveNothing) {
  ScratchDir dir;
  const std::vector<std::string> tables = MakeTables(dir / "tables", 4, 32);
  for (const auto& [sig, code] : {std::pair{SIGINT, 130}, std::pair{SIGHUP, 129}}) {
    const fs::path run = dir / ("run" + std::to_string(sig));
    fs::create_directories(run);
    // Interrupt while the run holds before its first fit, its report's lock taken (with its
    // pid written) and its interrupt hook installed (pipeline/batch_hold.h).
    const fs::path hold = dir / ("held" + std::to_string(sig));
    const pid_t pid = SpawnHeld(FitArgs(tables, run / "fits.h5"), run / "fit.log", hold, 0);
    ASSERT_TRUE(WaitForFile(hold, pid)) << ReadAll(run / "fit.log");
    EXPECT_THAT(ReadAll(run / ".fits.h5.lock"), HasSubstr(std::to_string(pid)));
    ASSERT_EQ(kill(pid, sig), 0);
    EXPECT_EQ(Wait(pid), code);
    EXPECT_THAT(ReadAll(run / "fit.log"), HasSubstr("fits kept, rerun to resume"));
    EXPECT_THAT(Leftovers(run), ::testing::IsEmpty());
  }
}

// ---- item 6: two writers -----------------------------------------------------------------

TEST(TwoWriters, ASecondFitOfTheSameReportRefusesAndNoFitIsLost) {
  ScratchDir dir;
  const std::vector<std::string> tables = MakeTables(dir / "tables", 4, 32);
  const fs::path report = dir / "fits.h5";
  // The first run holds before its first fit, its lock taken, until the second has tried.
  const fs::path hold = dir / "held";
  const pid_t first = SpawnHeld(FitArgs(tables, report), dir / "first.log", hold, 0);
  ASSERT_TRUE(WaitForFile(hold, first)) << ReadAll(dir / "first.log");
  const CliRun second = RunBrdfit(FitArgs(tables, report), dir / "second.log");
  EXPECT_EQ(second.code, 2) << second.log;
  EXPECT_THAT(second.log, HasSubstr(report.string() + ": is being written by another brdfit "
                                                      "process (pid " +
                                    std::to_string(first) + ")"));
  fs::remove(hold);
  EXPECT_EQ(Wait(first), 0) << ReadAll(dir / "first.log");
  EXPECT_EQ(ReadFitReport(report).size(), 2 * tables.size()) << "fits lost";
  EXPECT_FALSE(fs::exists(dir / ".fits.h5.lock")) << "lock file left after the run";
  // Once the first is done, the report is free again.
  const CliRun third = RunBrdfit(FitArgs(tables, report), dir / "third.log");
  EXPECT_EQ(third.code, 0) << third.log;
  EXPECT_THAT(third.log, HasSubstr("0 fits, " + std::to_string(2 * tables.size()) + " skipped"));
}

}  // namespace
}  // namespace brdfit
