// Nothing lost: a batch `brdfit fit` killed with SIGKILL mid-way leaves only complete outputs,
// and rerunning the same command resumes where it stopped and ends with exactly the report an
// uninterrupted run writes (byte for byte: --no-timings reports carry nothing run-dependent,
// io/fit_report.h). Inputs are never modified.
//
// The kill lands at a known point whatever the machine's speed: the batch runner's test hook
// (pipeline/batch_hold.h) writes a checkpoint after the run's kAfterFits-th fit and holds there,
// so the resumed run has exactly kAfterFits kept fits and the rest to make.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "cli_process.h"
#include "io/fit_report.h"
#include "io/hdf5_table.h"
#include "core/synth.h"
#include "models/registry.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

using testing_cli::ReadAll;
using testing_cli::Spawn;
using testing_cli::SpawnHeld;
using testing_cli::WaitForFile;
using testing_cli::Wait;

class KillResume : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("brdfit-kill-resume-" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // n synthetic tables (lambert+ggx, varied roughness and colour, 5 % noise) on a 32x32x64 grid.
  std::vector<std::string> MakeTables(int n) {
    Grid g;
    g.n_theta_h = 32;
    g.n_theta_d = 32;
    g.n_phi_d = 64;
    const ModelInfo* m = FindModel("lambert+ggx");
    std::vector<std::string> files;
    for (int i = 0; i < n; ++i) {
      const double kd = 0.2 + 0.05 * (i % 7), alpha = 0.05 + 0.04 * (i % 9);
      const std::vector<double> p = {kd, 0.8 * kd, 0.6 * kd, 0.4, 0.4, 0.4, alpha};
      SynthOptions so;
      so.noise = 0.05;
      so.seed = static_cast<std::uint64_t>(i + 1);
      const Table t = SynthesizeTable(
          g, [&](const Geometry& geo, double rgb[3]) { m->eval(p.data(), geo, rgb); }, so);
      const fs::path f = dir_ / "tables" / ("t" + std::to_string(i) + ".h5");
      fs::create_directories(f.parent_path());
      WriteHdf5Table(t, f);
      files.push_back(f.string());
    }
    return files;
  }

  std::vector<std::string> FitArgs(const std::vector<std::string>& tables, const fs::path& out) {
    std::vector<std::string> a = {"fit"};
    a.insert(a.end(), tables.begin(), tables.end());
    for (const char* s : {"--model", "ggx,ward", "--jobs", "2", "--no-timings", "--no-progress"}) {
      a.push_back(s);
    }
    a.insert(a.end(), {"--json", (out.parent_path() / "fits.json").string(), "-o", out.string()});
    return a;
  }

  fs::path dir_;
};

TEST_F(KillResume, KilledBatchLeavesCompleteOutputsAndResumesToTheSameReport) {
  constexpr int kTables = 8;
  constexpr std::size_t kAfterFits = 5;  // of 16: fits kept, fits in flight and fits to come
  fs::create_directories(dir_ / "run");
  fs::create_directories(dir_ / "ref");
  const std::vector<std::string> tables = MakeTables(kTables);
  std::map<std::string, std::string> inputs;
  for (const auto& t : tables) inputs[t] = ReadAll(t);
  const std::size_t total = 2 * tables.size();
  const fs::path report = dir_ / "run" / "fits.h5";

  // 1. Start the batch; SIGKILL it while it holds after the checkpoint of its kAfterFits-th fit
  //    (the other worker is inside a fit then, or waiting to record one).
  const fs::path hold = dir_ / "held";
  const pid_t pid = SpawnHeld(FitArgs(tables, report), dir_ / "run.log", hold, kAfterFits);
  ASSERT_TRUE(WaitForFile(hold, pid)) << "the batch ended before its hold point:\n"
                                      << ReadAll(dir_ / "run.log");
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  ASSERT_EQ(Wait(pid), 128 + SIGKILL);

  // 2. Only complete outputs: the report reads; anything else is an atomic writer's
  //    temporary (".<name>.tmp-<pid>-<n>"), never a partial file under a final name.
  std::size_t kept = 0;
  std::vector<std::string> temporaries;
  ASSERT_TRUE(fs::exists(report)) << "no checkpoint before the kill";
  for (const auto& e : fs::directory_iterator(dir_ / "run")) {
    const std::string name = e.path().filename().string();
    if (name == ".fits.h5.lock") continue;  // the report's lock (io/file_lock.h)
    if (name == "fits.h5") {
      std::vector<FitReportEntry> entries;
      ASSERT_NO_THROW(entries = ReadFitReport(e.path())) << "partial report after SIGKILL";
      kept = entries.size();
      for (const auto& en : entries) EXPECT_FALSE(en.result.Failed()) << en.result.message;
    } else {
      temporaries.push_back(name);
      EXPECT_TRUE(name.starts_with(".fits.h5.tmp-") || name.starts_with(".fits.json.tmp-"))
          << "unexpected file after SIGKILL: " << name;
    }
  }
  EXPECT_FALSE(fs::exists(dir_ / "run" / "fits.json")) << "the JSON is written at the end";
  std::printf("killed a batch of %zu fits (%d tables) holding a checkpoint of %zu; %zu "
              "temporary file(s) left by the kill\n",
              total, kTables, kept, temporaries.size());
  ASSERT_EQ(kept, kAfterFits) << "the checkpoint does not hold the fits made before the hold";

  // 3. Rerun: resumes (the kept fits are skipped, the others fitted) and completes.
  EXPECT_EQ(Wait(Spawn(FitArgs(tables, report), dir_ / "resume.log")), 0)
      << ReadAll(dir_ / "resume.log");
  const std::string log = ReadAll(dir_ / "resume.log");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(log, m, std::regex(R"((\d+) fits, (\d+) skipped)"))) << log;
  EXPECT_EQ(std::stoul(m[2]), kept) << log;
  EXPECT_EQ(std::stoul(m[1]), total - kept) << log;

  // 4. The same report and JSON as an uninterrupted run, byte for byte.
  const fs::path ref = dir_ / "ref" / "fits.h5";
  EXPECT_EQ(Wait(Spawn(FitArgs(tables, ref), dir_ / "ref.log")), 0) << ReadAll(dir_ / "ref.log");
  EXPECT_EQ(ReadFitReport(report).size(), total);
  EXPECT_TRUE(ReadAll(report) == ReadAll(ref)) << "resumed report differs from the reference";
  EXPECT_TRUE(ReadAll(dir_ / "run" / "fits.json") == ReadAll(dir_ / "ref" / "fits.json"));

  // 5. Inputs untouched.
  for (const auto& [file, bytes] : inputs) EXPECT_TRUE(ReadAll(file) == bytes) << file;
}

}  // namespace
}  // namespace brdfit
