// Nothing lost: a batch `brdfit fit` killed with SIGKILL mid-way leaves only complete outputs,
// and rerunning the same command resumes where it stopped and ends with exactly the report an
// uninterrupted run writes (byte for byte: --no-timings reports carry nothing run-dependent,
// io/fit_report.h). Inputs are never modified.
//
// The kill lands after the first checkpoint of the report (cli/cmd_fit.cc writes one every few
// seconds) plus a short delay, so that the resumed run has both kept and fresh fits. If the
// machine is fast enough to finish the batch before that, the batch is doubled and retried.
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
    // --budget full: fits slow enough (tens of ms each) that a kill lands between checkpoints.
    for (const char* s : {"--model", "ggx,ward", "--multistart", "2", "--budget", "full",
                          "--no-timings", "--no-progress"}) {
      a.push_back(s);
    }
    a.insert(a.end(), {"--json", (out.parent_path() / "fits.json").string(), "-o", out.string()});
    return a;
  }

  fs::path dir_;
};

TEST_F(KillResume, KilledBatchLeavesCompleteOutputsAndResumesToTheSameReport) {
  for (int n_tables = 8; n_tables <= 64; n_tables *= 2) {
    fs::remove_all(dir_ / "run");
    fs::remove_all(dir_ / "ref");
    fs::create_directories(dir_ / "run");
    fs::create_directories(dir_ / "ref");
    const std::vector<std::string> tables = MakeTables(n_tables);
    std::map<std::string, std::string> inputs;
    for (const auto& t : tables) inputs[t] = ReadAll(t);
    const std::size_t total = 2 * tables.size();
    const fs::path report = dir_ / "run" / "fits.h5";

    // 1. Start the batch; SIGKILL it shortly after its first checkpoint appears.
    const pid_t pid = Spawn(FitArgs(tables, report), dir_ / "run.log");
    bool killed = false;
    for (int polls = 0; polls < 60000 && !killed; ++polls) {
      int status;
      if (waitpid(pid, &status, WNOHANG) == pid) break;  // finished before a checkpoint
      if (fs::exists(report)) {
        std::this_thread::sleep_for(700ms);  // let it get into the next fits, or a checkpoint
        killed = kill(pid, SIGKILL) == 0 && Wait(pid) == 128 + SIGKILL;
        break;
      }
      std::this_thread::sleep_for(10ms);
    }
    if (!killed) {
      waitpid(pid, nullptr, 0);
      continue;  // too fast for this batch size: double it
    }

    // 2. Only complete outputs: the report (if any) reads; anything else is an atomic writer's
    //    temporary (".<name>.tmp-<pid>-<n>"), never a partial file under a final name.
    std::size_t kept = 0;
    std::vector<std::string> temporaries;
    for (const auto& e : fs::directory_iterator(dir_ / "run")) {
      const std::string name = e.path().filename().string();
      if (name == ".fits.h5.lock") continue;  // the report's lock (io/file_lock.h)
      if (name != "fits.h5") temporaries.push_back(name);
      if (name == "fits.h5") {
        std::vector<FitReportEntry> entries;
        ASSERT_NO_THROW(entries = ReadFitReport(e.path())) << "partial report after SIGKILL";
        kept = entries.size();
        for (const auto& en : entries) EXPECT_FALSE(en.result.Failed()) << en.result.message;
      } else {
        EXPECT_TRUE(name.starts_with(".fits.h5.tmp-") || name.starts_with(".fits.json.tmp-"))
            << "unexpected file after SIGKILL: " << name;
      }
    }
    EXPECT_FALSE(fs::exists(dir_ / "run" / "fits.json")) << "the JSON is written at the end";
    std::printf("killed a batch of %zu fits (%d tables) holding a checkpoint of %zu; %zu "
                "temporary file(s) left by the kill\n",
                total, n_tables, kept, temporaries.size());
    ASSERT_GT(kept, 0u) << "the checkpoint holds no fit";
    ASSERT_LT(kept, total) << "killed after the last fit: nothing left to resume";

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
    return;
  }
  FAIL() << "every batch finished before its first checkpoint could be interrupted";
}

}  // namespace
}  // namespace brdfit
