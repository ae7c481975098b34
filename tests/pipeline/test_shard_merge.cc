// Batches beyond one machine (issue 17, docs/scale.md): `brdfit fit --shard I/N` slices the
// work list, `brdfit merge` joins the slices' reports, and the merged report is the report of
// one process doing the same work, byte for byte (--no-timings reports hold nothing
// run-dependent, io/fit_report.h). Also: the slicing itself (a partition, balanced, not
// depending on the order of the inputs), conflicting and identical duplicates, the GNU
// parallel recipe, and the job-log progress lines of a fit whose stderr is a pipe.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <H5Cpp.h>

#include "core/error.h"
#include "core/provenance.h"
#include "core/synth.h"
#include "fit/fitter.h"
#include "io/fit_report.h"
#include "io/hdf5_table.h"
#include "io/hdf5_util.h"
#include "models/registry.h"
#include "pipeline/shard.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using pipeline::Shard;
using pipeline::ShardMembership;
using pipeline::ShardRun;

std::string ReadAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// ---- the slicing ----------------------------------------------------------------------------

TEST(ShardSpec, ParsesIOverNAndRefusesTheRest) {
  const Shard s = pipeline::ParseShard("2/7");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 7);
  EXPECT_TRUE(pipeline::ParseShard("0/1").Whole());
  for (const char* bad :
       {"", "3", "7/7", "8/7", "-1/3", "1/0", "a/3", "1/3x", "1/", "/3", "0/1000000"}) {
    EXPECT_THROW(pipeline::ParseShard(bad), InputError) << bad;
  }
}

std::vector<std::string> Inputs(int n) {
  std::vector<std::string> v;
  for (int i = 0; i < n; ++i) v.push_back("tables/t" + std::to_string(i) + ".h5");
  return v;
}

const std::vector<ShardRun> kRuns = {{"lambert+ggx", "{\"loss\":\"rel\"}"},
                                     {"lambert+ggx+ggx", "{\"loss\":\"rel\"}"},
                                     {"lambert+abc", "{\"loss\":\"logratio\"}"}};

// Every item in exactly one of the N shards; the most and least loaded shards differ by at
// most one unit's cost (a whole input's with >= N inputs, else the dearest model's).
TEST(ShardMembership, PartitionsTheWorkListAndBalancesItsCost) {
  int unit_max = 0, run_max = 0;
  for (const ShardRun& r : kRuns) {
    unit_max += pipeline::ModelRunCost(r.model);
    run_max = std::max(run_max, pipeline::ModelRunCost(r.model));
  }
  EXPECT_GT(pipeline::ModelRunCost("lambert+ggx+ggx"), pipeline::ModelRunCost("lambert+ggx"));
  for (int n_inputs : {1, 2, 5, 40}) {
    const std::vector<std::string> inputs = Inputs(n_inputs);
    for (int n : {1, 2, 3, 7, 16}) {
      std::vector<int> owners(inputs.size() * kRuns.size(), 0);
      std::vector<int> load(n, 0);
      for (int i = 0; i < n; ++i) {
        const std::vector<bool> in = ShardMembership(inputs, kRuns, {i, n});
        ASSERT_EQ(in.size(), owners.size());
        for (std::size_t k = 0; k < in.size(); ++k) {
          owners[k] += in[k];
          if (in[k]) load[i] += pipeline::ModelRunCost(kRuns[k % kRuns.size()].model);
        }
      }
      for (int o : owners) EXPECT_EQ(o, 1) << n_inputs << " inputs, " << n << " shards";
      const int spread =
          *std::max_element(load.begin(), load.end()) - *std::min_element(load.begin(), load.end());
      EXPECT_LE(spread, n_inputs >= n ? unit_max : run_max)
          << n_inputs << " inputs, " << n << " shards";
    }
  }
}

// The costs are measured (pipeline/shard.cc, docs/scale.md "Cost of a fit") for every model of
// the catalog; a model added since needs its measurement. What the measurement found and the
// parameter count did not predict: lambert+abc costs far more than lambert+ggx+ggx.
TEST(ShardMembership, EveryFittableModelHasAMeasuredCost) {
  for (const std::string& m : FittableModels()) {
    EXPECT_TRUE(pipeline::HasMeasuredRunCost(m))
        << m << ": no measured cost; measure it as docs/scale.md \"Cost of a fit\" says";
    EXPECT_GT(pipeline::ModelRunCost(m), 0) << m;
  }
  EXPECT_GT(pipeline::ModelRunCost("lambert+abc"), pipeline::ModelRunCost("lambert+ggx+ggx"));
  EXPECT_LT(FindModel("lambert+abc")->params.size(), FindModel("lambert+ggx+ggx")->params.size());
  // Unmeasured: the rough guess, 10 + parameters.
  EXPECT_FALSE(pipeline::HasMeasuredRunCost("no-such-model"));
  EXPECT_EQ(pipeline::ModelRunCost("no-such-model"), 10);
}

// A shell glob sorts by locale: the same set of inputs in another order gives each item the
// same shard.
TEST(ShardMembership, DoesNotDependOnTheOrderOfTheInputs) {
  for (int n_inputs : {3, 40}) {
    const std::vector<std::string> inputs = Inputs(n_inputs);
    std::vector<std::string> reversed(inputs.rbegin(), inputs.rend());
    for (int i = 0; i < 7; ++i) {
      const std::vector<bool> a = ShardMembership(inputs, kRuns, {i, 7});
      const std::vector<bool> b = ShardMembership(reversed, kRuns, {i, 7});
      for (std::size_t f = 0; f < inputs.size(); ++f) {
        for (std::size_t k = 0; k < kRuns.size(); ++k) {
          EXPECT_EQ(a[f * kRuns.size() + k], b[(inputs.size() - 1 - f) * kRuns.size() + k]);
        }
      }
    }
  }
}

// ---- the CLI: fit --shard, merge ------------------------------------------------------------

class ShardCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("brdfit-shard-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "tables");
    // 5 tables (lambert+ggx, varied roughness and colour, 3 % noise) on a 16x16x32 grid.
    Grid g;
    g.n_theta_h = 16;
    g.n_theta_d = 16;
    g.n_phi_d = 32;
    const ModelInfo* m = FindModel("lambert+ggx");
    for (int i = 0; i < 5; ++i) {
      const double kd = 0.2 + 0.07 * i, alpha = 0.06 + 0.08 * i;
      const std::vector<double> p = {kd, 0.8 * kd, 0.6 * kd, 0.4, 0.4, 0.4, alpha};
      SynthOptions so;
      so.noise = 0.03;
      so.seed = static_cast<std::uint64_t>(i + 1);
      const Table t = SynthesizeTable(
          g, [&](const Geometry& geo, double rgb[3]) { m->eval(p.data(), geo, rgb); }, so);
      const fs::path f = dir_ / "tables" / ("t" + std::to_string(i) + ".h5");
      WriteHdf5Table(t, f);
      tables_.push_back(f.string());
    }
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // `brdfit ARGS` through the shell, stdout and stderr to a log; the exit code.
  int Run(const std::string& args, std::string* log = nullptr, const std::string& env = "") {
    const fs::path l = dir_ / "cli.log";
    const std::string cmd =
        env + " '" + std::string(BRDFIT_EXE) + "' " + args + " > '" + l.string() + "' 2>&1";
    const int status = std::system(cmd.c_str());
    if (log) *log = ReadAll(l);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  // The fit command of the batch (three fast models), without -o.
  std::string FitArgs(const std::string& extra = "", bool timings = false) const {
    std::string a = "fit";
    for (const auto& t : tables_) a += " '" + t + "'";
    return a + " --model ggx,blinn-phong,ward --budget full --no-progress -q " +
           (timings ? "" : "--no-timings ") + extra;
  }
  std::string P(const std::string& name) const { return "'" + (dir_ / name).string() + "'"; }

  fs::path dir_;
  std::vector<std::string> tables_;
};

TEST_F(ShardCli, ShardedAndMergedEqualsUnshardedByteForByte) {
  std::string log;
  ASSERT_EQ(Run(FitArgs("-o " + P("ref.h5")), &log), 0) << log;
  const std::string ref = ReadAll(dir_ / "ref.h5");
  const std::vector<FitReportEntry> ref_entries = ReadFitReport(dir_ / "ref.h5");
  ASSERT_EQ(ref_entries.size(), 15u);
  std::map<std::string, std::string> inputs;
  for (const auto& t : tables_) inputs[t] = ReadAll(t);

  for (int n : {1, 2, 3, 7}) {
    std::string parts;
    std::size_t fits = 0;
    for (int i = 0; i < n; ++i) {
      const std::string part = "shard-" + std::to_string(n) + "-" + std::to_string(i) + ".h5";
      ASSERT_EQ(
          Run(FitArgs("--shard " + std::to_string(i) + "/" + std::to_string(n) + " -o " + P(part)),
              &log),
          0)
          << log;
      if (!fs::exists(dir_ / part)) continue;  // 7 shards of 15 fits: none is empty, but allow
      const std::vector<FitReportEntry> e = ReadFitReport(dir_ / part);
      fits += e.size();
      // A shard marks a table's choice only when it holds all that table's fits: then the
      // mark is the unsharded one.
      std::map<std::string, int> per_source;
      for (const auto& x : e) ++per_source[x.source];
      for (const auto& x : e) {
        if (per_source[x.source] < 3) {
          EXPECT_FALSE(x.chosen) << part << ": split source " << x.source << " marked";
          continue;
        }
        const auto same = std::find_if(ref_entries.begin(), ref_entries.end(), [&](auto& r) {
          return r.source == x.source && r.result.model == x.result.model;
        });
        ASSERT_NE(same, ref_entries.end());
        EXPECT_EQ(x.chosen, same->chosen) << part << " " << x.source << " " << x.result.model;
      }
      parts += " " + P(part);
    }
    EXPECT_EQ(fits, 15u) << n << " shards: every fit exactly once";
    const std::string out = "merged-" + std::to_string(n) + ".h5";
    ASSERT_EQ(Run("merge " + P(out) + parts, &log), 0) << log;
    EXPECT_NE(log.find("15 fits from " + std::to_string(n) + " parts"), std::string::npos) << log;
    EXPECT_TRUE(ReadAll(dir_ / out) == ref) << n << " shards: merged report differs from the "
                                            << "unsharded one";
  }
  for (const auto& [t, bytes] : inputs) EXPECT_TRUE(ReadAll(t) == bytes) << t << " modified";
}

TEST_F(ShardCli, MergeKeepsIdenticalDuplicatesOnceAndRefusesConflicts) {
  std::string log;
  ASSERT_EQ(Run(FitArgs("-o " + P("ref.h5")), &log), 0) << log;
  ASSERT_EQ(Run(FitArgs("--shard 0/2 -o " + P("s0.h5")), &log), 0) << log;
  ASSERT_EQ(Run(FitArgs("--shard 1/2 -o " + P("s1.h5")), &log), 0) << log;
  const std::string ref = ReadAll(dir_ / "ref.h5");

  // Identical duplicates (the whole report and both shards): kept once.
  ASSERT_EQ(
      Run("merge " + P("m.h5") + " " + P("s0.h5") + " " + P("ref.h5") + " " + P("s1.h5"), &log), 0)
      << log;
  EXPECT_NE(log.find("15 fits from 3 parts (30 read, 15 identical duplicates"), std::string::npos)
      << log;
  EXPECT_TRUE(ReadAll(dir_ / "m.h5") == ref);

  // A timed run of the same work is the same results: merges with the untimed one, keeps the
  // first part's timings.
  ASSERT_EQ(Run(FitArgs("--shard 0/2 -o " + P("timed.h5"), /*timings=*/true), &log), 0) << log;
  ASSERT_EQ(Run("merge " + P("mt.h5") + " " + P("timed.h5") + " " + P("ref.h5"), &log), 0) << log;
  const std::vector<FitReportEntry> mt = ReadFitReport(dir_ / "mt.h5");
  const std::vector<FitReportEntry> timed = ReadFitReport(dir_ / "timed.h5");
  ASSERT_EQ(mt.size(), 15u);
  ASSERT_FALSE(timed.empty());
  for (const FitReportEntry& t : timed) {
    const auto same = std::find_if(mt.begin(), mt.end(), [&](auto& m) {
      return m.source == t.source && m.result.model == t.result.model;
    });
    ASSERT_NE(same, mt.end());
    EXPECT_TRUE(same->timed);
    EXPECT_GT(same->result.times.solve, 0);
    EXPECT_EQ(same->result.times.solve, t.result.times.solve);
  }
  ASSERT_EQ(
      Run("merge --no-timings " + P("mnt.h5") + " " + P("timed.h5") + " " + P("ref.h5"), &log), 0)
      << log;
  EXPECT_TRUE(ReadAll(dir_ / "mnt.h5") == ref);

  // A shard killed after some of its fits (its last checkpoint: a report holding them, marks
  // as written) resumes: the rerun skips them and ends with the uninterrupted shard's report.
  {
    std::vector<FitReportEntry> some = ReadFitReport(dir_ / "s0.h5");
    ASSERT_GE(some.size(), 2u);
    some.resize(some.size() / 2);
    WriteFitReport(some, dir_ / "killed.h5", false);
    std::string rerun = FitArgs("--shard 0/2 -o " + P("killed.h5"));
    rerun.replace(rerun.find(" -q "), 4, " ");
    ASSERT_EQ(Run(rerun, &log), 0) << log;
    EXPECT_NE(log.find(std::to_string(some.size()) + " skipped"), std::string::npos) << log;
    EXPECT_TRUE(ReadAll(dir_ / "killed.h5") == ReadAll(dir_ / "s0.h5"));
  }

  // A conflict: one fit of s1 with another result.
  std::vector<FitReportEntry> e = ReadFitReport(dir_ / "s1.h5");
  ASSERT_FALSE(e.empty());
  e[0].result.final_cost = 1.5 * e[0].result.final_cost + 1e-3;
  WriteFitReport(e, dir_ / "bad.h5", false);
  const std::string s0 = ReadAll(dir_ / "s0.h5"), bad = ReadAll(dir_ / "bad.h5");
  EXPECT_EQ(
      Run("merge " + P("c.h5") + " " + P("s0.h5") + " " + P("ref.h5") + " " + P("bad.h5"), &log),
      2);
  EXPECT_NE(log.find("conflicting fits of " + e[0].source), std::string::npos) << log;
  EXPECT_NE(log.find((dir_ / "ref.h5").string() + " and " + (dir_ / "bad.h5").string()),
            std::string::npos)
      << log;
  EXPECT_FALSE(fs::exists(dir_ / "c.h5"));
  EXPECT_TRUE(ReadAll(dir_ / "s0.h5") == s0 && ReadAll(dir_ / "bad.h5") == bad &&
              ReadAll(dir_ / "ref.h5") == ref)
      << "merge modified a part";

  // The output may not be a part; a missing or unreadable part is named.
  EXPECT_EQ(Run("merge " + P("s0.h5") + " " + P("s0.h5") + " " + P("s1.h5"), &log), 2);
  EXPECT_TRUE(ReadAll(dir_ / "s0.h5") == s0);
  EXPECT_EQ(Run("merge " + P("x.h5") + " " + P("nope.h5"), &log), 2);
  EXPECT_NE(log.find("nope.h5"), std::string::npos) << log;
  EXPECT_EQ(Run("merge " + P("x.h5") + " '" + tables_[0] + "'", &log), 2);
  EXPECT_NE(log.find(tables_[0]), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir_ / "x.h5"));
  EXPECT_EQ(Run(FitArgs("--shard 3/3 -o " + P("y.h5")), &log), 2);
  EXPECT_NE(log.find("--shard '3/3'"), std::string::npos) << log;
}

// Resume keeps a fit only of the table it was made from: a table rewritten under the same name
// with other contents is fitted again (its old entries replaced, the change said on stderr);
// the other tables' fits stay skipped (docs/scale.md, "Resume and merge: what must agree").
TEST_F(ShardCli, ResumeRefitsATableWhoseContentsChanged) {
  std::string log;
  ASSERT_EQ(Run(FitArgs("-o " + P("r.h5")), &log), 0) << log;
  const std::vector<FitReportEntry> before = ReadFitReport(dir_ / "r.h5");
  std::string old_hash;
  for (const auto& e : before) {
    if (e.source == tables_[0]) old_hash = e.source_hash;
  }
  ASSERT_FALSE(old_hash.empty());
  // t0.h5 regenerated with other contents (table 4's) under the same name.
  const Table other = ReadHdf5Table(tables_[4]);
  fs::remove(tables_[0]);
  WriteHdf5Table(other, tables_[0]);
  const std::string new_hash = TableContentHash(other);
  ASSERT_NE(new_hash, old_hash);
  std::string rerun = FitArgs("-o " + P("r.h5"));
  rerun.replace(rerun.find(" -q "), 4, " ");
  ASSERT_EQ(Run(rerun, &log), 0) << log;
  EXPECT_NE(log.find("3 fits, 12 skipped"), std::string::npos) << log;
  EXPECT_NE(log.find("brdfit: note: " + tables_[0] +
                     ": its contents changed since the report's "
                     "fits (content hash " +
                     old_hash + ", now " + new_hash + "): fitted again"),
            std::string::npos)
      << log;
  const std::vector<FitReportEntry> after = ReadFitReport(dir_ / "r.h5");
  ASSERT_EQ(after.size(), 15u);
  for (const auto& e : after) {
    if (e.source == tables_[0]) {
      EXPECT_EQ(e.source_hash, new_hash) << e.result.model;
    }
  }
  // The report is now the one a fresh run of the new tables writes.
  ASSERT_EQ(Run(FitArgs("-o " + P("fresh.h5")), &log), 0) << log;
  EXPECT_TRUE(ReadAll(dir_ / "r.h5") == ReadAll(dir_ / "fresh.h5"));
  // A third run: nothing changed, everything skipped.
  ASSERT_EQ(Run(rerun, &log), 0) << log;
  EXPECT_NE(log.find("0 fits, 15 skipped"), std::string::npos) << log;
  EXPECT_EQ(log.find("contents changed"), std::string::npos) << log;
}

// Merge joins the parts of one batch only: refused, naming both parts, when a model was fitted
// under other options in another part, a material to other table contents, or the parts were
// written by two brdfit versions. Nothing is written then, and the parts are untouched.
TEST_F(ShardCli, MergeRefusesPartsOfDifferentRunsNamingBoth) {
  std::string log;
  ASSERT_EQ(Run(FitArgs("--shard 0/2 -o " + P("s0.h5")), &log), 0) << log;
  ASSERT_EQ(Run(FitArgs("--shard 1/2 -o " + P("s1.h5")), &log), 0) << log;
  // Shard 1 again, under another loss.
  ASSERT_EQ(Run(FitArgs("--shard 1/2 --loss log -o " + P("s1log.h5")), &log), 0) << log;
  const std::string s0 = ReadAll(dir_ / "s0.h5"), s1log = ReadAll(dir_ / "s1log.h5");
  EXPECT_EQ(Run("merge " + P("m.h5") + " " + P("s0.h5") + " " + P("s1log.h5"), &log), 2) << log;
  EXPECT_NE(log.find("was fitted with options"), std::string::npos) << log;
  EXPECT_NE(log.find("\"loss\":\"rel\""), std::string::npos) << log;
  EXPECT_NE(log.find("\"loss\":\"log\""), std::string::npos) << log;
  EXPECT_NE(log.find((dir_ / "s0.h5").string()), std::string::npos) << log;
  EXPECT_NE(log.find((dir_ / "s1log.h5").string()), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir_ / "m.h5"));
  EXPECT_TRUE(ReadAll(dir_ / "s0.h5") == s0 && ReadAll(dir_ / "s1log.h5") == s1log);

  // One material fitted to other contents in another part.
  std::vector<FitReportEntry> stale = ReadFitReport(dir_ / "s0.h5");
  ASSERT_FALSE(stale.empty());
  for (auto& e : stale) e.source_hash = std::string(e.source_hash.size(), 'f');
  WriteFitReport(stale, dir_ / "stale.h5", false);
  EXPECT_EQ(Run("merge " + P("m.h5") + " " + P("s0.h5") + " " + P("stale.h5"), &log), 2) << log;
  EXPECT_NE(log.find("the table changed between the runs"), std::string::npos) << log;
  EXPECT_NE(log.find(stale[0].source_hash), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir_ / "m.h5"));

  // Another brdfit version wrote one part.
  fs::copy_file(dir_ / "s1.h5", dir_ / "s1old.h5");
  {
    H5::H5File f((dir_ / "s1old.h5").string(), H5F_ACC_RDWR);
    f.removeAttr("brdfit_version");
    hdf5::WriteStringAttr(f, "brdfit_version", "0.0.9-other");
  }
  EXPECT_EQ(Run("merge " + P("m.h5") + " " + P("s0.h5") + " " + P("s1old.h5"), &log), 2) << log;
  EXPECT_NE(log.find("by brdfit 0.0.9-other"), std::string::npos) << log;
  EXPECT_NE(log.find((dir_ / "s1old.h5").string()), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir_ / "m.h5"));
  // The shards of one run still merge.
  EXPECT_EQ(Run("merge " + P("m.h5") + " " + P("s0.h5") + " " + P("s1.h5"), &log), 0) << log;
}

// Every report a fit writes reads back, so that it resumes and merges: an ABC fit of
// nbrdf:black-fabric ended one ulp beyond abc.c's upper bound (exp(log 10)), and its rerun and
// merge refused the report (fit/fit_engine.cc clamps into the bounds).
TEST_F(ShardCli, AFitOnItsUpperBoundResumesAndMerges) {
  const fs::path zip = fs::path(BRDFIT_SHARED_DATA) / "merl_nbrdf.zip";
  if (!fs::exists(zip)) GTEST_SKIP() << zip << " is absent: the NBRDF case is not tested";
  const std::string env = "BRDFIT_NBRDF_ZIP='" + zip.string() + "'";
  const std::string fit = "fit nbrdf:black-fabric --model abc --no-timings --no-progress -q -o ";
  std::string log;
  ASSERT_EQ(Run(fit + P("bf.h5"), &log, env), 0) << log;
  const std::vector<FitReportEntry> e = ReadFitReport(dir_ / "bf.h5");
  ASSERT_EQ(e.size(), 1u);
  const ModelInfo* m = FindModel(e[0].result.model);
  ASSERT_NE(m, nullptr);
  bool on_bound = false;
  for (std::size_t k = 0; k < e[0].result.params.size(); ++k) {
    on_bound = on_bound || e[0].result.params[k] == m->params[k].upper;
  }
  EXPECT_TRUE(on_bound) << "the case no longer ends on a bound: pick another";
  const std::string first = ReadAll(dir_ / "bf.h5");
  ASSERT_EQ(Run(fit.substr(0, fit.find(" -q ")) + " -o " + P("bf.h5"), &log, env), 0) << log;
  EXPECT_NE(log.find("0 fits, 1 skipped"), std::string::npos) << log;
  EXPECT_TRUE(ReadAll(dir_ / "bf.h5") == first);
  ASSERT_EQ(Run("merge " + P("m.h5") + " " + P("bf.h5"), &log), 0) << log;
  EXPECT_TRUE(ReadAll(dir_ / "m.h5") == ReadAll(dir_ / "bf.h5"));
}

// The recipe of docs/scale.md: GNU parallel runs the shards, brdfit merge joins them.
TEST_F(ShardCli, GnuParallelShardsMergeToTheUnshardedReport) {
  if (std::system("command -v parallel >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "GNU parallel is not installed (Debian package parallel, "
                    "scripts/setup-deps.sh): the recipe is not tested";
  }
  std::string log;
  ASSERT_EQ(Run(FitArgs("-o " + P("ref.h5")), &log), 0) << log;
  const std::string fit =
      "'" + std::string(BRDFIT_EXE) + "' " + FitArgs("--shard {}/3 -o " + P("part-{}.h5"));
  const std::string cmd = "cd '" + dir_.string() +
                          "' && parallel --will-cite --halt now,fail=1 "
                          "--jobs 2 " +
                          fit + " ::: 0 1 2 > parallel.log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << ReadAll(dir_ / "parallel.log");
  ASSERT_EQ(Run("merge " + P("merged.h5") + " " + P("part-0.h5") + " " + P("part-1.h5") + " " +
                    P("part-2.h5"),
                &log),
            0)
      << log;
  EXPECT_TRUE(ReadAll(dir_ / "merged.h5") == ReadAll(dir_ / "ref.h5"));
}

// stderr a pipe (a job log): one time-stamped line per finished fit, summaries with rate and
// ETA (every item with BRDFIT_PROGRESS_INTERVAL=0), one at the end.
TEST_F(ShardCli, JobLogGetsOneLinePerFinishedFitAndSummaries) {
  std::string a = "fit";
  for (const auto& t : tables_) a += " '" + t + "'";
  // -j 2: fits start before the previous ones finished (each is logged once, when it ends).
  a += " --model ggx,ward --budget full -j 2 -o " + P("fits.h5") + " 2>&1 >/dev/null | cat > " +
       P("stderr.txt");
  const std::string cmd =
      "BRDFIT_PROGRESS_INTERVAL=0 BRDFIT_NO_PROGRESS= '" + std::string(BRDFIT_EXE) + "' " + a;
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string err = ReadAll(dir_ / "stderr.txt");
  const std::regex done(R"(^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ fitting (\d+)/10 done: (\S+) )"
                        R"(\S+ rel \((converged|no_convergence)\)$)");
  const std::regex summary(R"(^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ fitting (\d+)/10 \(\d+%\), )"
                           R"((?:[0-9.e+]+/s|\S+/item), elapsed \S+, ETA \S+$)");
  std::istringstream in(err);
  std::string line;
  std::vector<int> done_counts;
  int summaries = 0;
  std::string last;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, done)) {
      done_counts.push_back(std::stoi(m[1]));
    } else if (std::regex_match(line, m, summary)) {
      ++summaries;
    } else {
      ADD_FAILURE() << "unexpected line: " << line;
    }
    last = line;
  }
  ASSERT_EQ(done_counts.size(), 10u) << err;
  for (int i = 0; i < 10; ++i) EXPECT_EQ(done_counts[i], i + 1) << err;
  EXPECT_EQ(summaries, 10) << err;  // after fits 1..9, and the final one
  EXPECT_NE(last.find("fitting 10/10 (100%)"), std::string::npos) << err;
  EXPECT_NE(last.find("ETA 0s"), std::string::npos) << err;
}

// stderr a terminal (a pseudo-terminal from util-linux script(1)): the bar, redrawn in place,
// shows the rate and the ETA.
TEST_F(ShardCli, TerminalBarShowsRateAndEta) {
  if (std::system("command -v script >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "script(1) (util-linux) is absent: no pseudo-terminal to test the bar on";
  }
  std::string a = "'" + std::string(BRDFIT_EXE) + "' fit";
  for (const auto& t : tables_) a += " '" + t + "'";
  a += " --model ggx,ward --budget full -o " + P("fits.h5");
  const std::string cmd = "BRDFIT_NO_PROGRESS= script -qec \"" + a + "\" /dev/null > " +
                          P("tty.txt") + " 2>&1 < /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << ReadAll(dir_ / "tty.txt");
  const std::string out = ReadAll(dir_ / "tty.txt");
  const std::regex bar(
      R"(\r\x1b\[2Kfitting \[[#.]{24}\] (\d+)/10 [0-9.e+]+/s, elapsed \S+, ETA \S+ )");
  const auto n =
      std::distance(std::sregex_iterator(out.begin(), out.end(), bar), std::sregex_iterator());
  EXPECT_GE(n, 9) << out;  // a redraw after every finished fit but the first start
  EXPECT_NE(out.find("fitting [########################] 10/10"), std::string::npos) << out;
  EXPECT_EQ(out.find(" done: "), std::string::npos) << "job-log lines on a terminal";
}

}  // namespace
}  // namespace brdfit
