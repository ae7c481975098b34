// `brdfit factor --shard I/N` and `brdfit bench --shard I/N` (issue 17 items 1-2,
// docs/scale.md): the shards' output folders and CSVs, joined by `brdfit merge`, equal the
// single-process outputs byte for byte (--no-timings), for N = 1, 2, 3; identical duplicates
// are kept once, conflicts refused naming both parts. The tables a/x.h5, b/x.h5 (one stem, two
// folders) and a/y.h5 are three materials: factor outputs a_x.*, b_x.*, a_y.*.
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "core/synth.h"
#include "io/hdf5_table.h"
#include "models/registry.h"
#include "report/bench_csv.h"
#include "tests/pipeline/lab_tables.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;

using testing::ReadAll;

// Every regular file of a folder: name -> bytes.
std::map<std::string, std::string> Folder(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& d : fs::directory_iterator(dir)) {
    if (d.is_regular_file()) out[d.path().filename().string()] = ReadAll(d.path());
  }
  return out;
}

class ShardFactorBench : public testing::LabTables {
 protected:
  void SetUp() override { MakeTables("shard-fb", {0.3, 0.2, 0.15, 0.5, 0.5, 0.5}, 0.1, 0.12, 7); }
  static constexpr const char* kTables = "lab/a/x.h5 lab/b/x.h5 lab/a/y.h5";
  static std::string Factor(const std::string& extra) {
    return std::string("factor ") + kTables + " --no-auto --param halfdiff --res 8 -q " + extra;
  }
  static std::string Bench(const std::string& extra) {
    return std::string("bench ") + kTables +
           " --models lambert+ggx --budgets full,stride:4 --losses log -q " + extra;
  }
};

TEST_F(ShardFactorBench, FactorShardsMergeToTheUnshardedFolderByteForByte) {
  std::string log;
  ASSERT_EQ(Run(Factor("--no-timings -o ref"), &log), 0) << log;
  const auto ref = Folder(dir_ / "ref");
  // Three materials, named by their keys; the run-dependent members are gone.
  for (const char* stem : {"a_x", "b_x", "a_y"}) {
    ASSERT_TRUE(ref.count(std::string(stem) + ".factor.json")) << stem;
    const std::string j = ref.at(std::string(stem) + ".factor.json");
    EXPECT_EQ(j.find("\"seconds\""), std::string::npos) << stem;
    EXPECT_EQ(j.find("system_reused"), std::string::npos) << stem;
    EXPECT_EQ(j.find("command_line"), std::string::npos) << stem;
  }
  EXPECT_EQ(ref.size(), 9u);  // a sidecar and two textures each
  EXPECT_NE(ref.at("a_x.p.exr"), ref.at("b_x.p.exr")) << "two tables, one result";
  for (int n : {1, 2, 3}) {
    std::string parts;
    std::size_t files = 0;
    for (int i = 0; i < n; ++i) {
      const std::string part = fmt::format("f{}-{}", n, i);
      ASSERT_EQ(Run(Factor("--no-timings --shard " + std::to_string(i) + "/" + std::to_string(n) +
                           " -o " + part),
                    &log),
                0)
          << log;
      files += Folder(dir_ / part).size();
      parts += " " + part;
    }
    EXPECT_EQ(files, ref.size()) << n << " shards: every table exactly once";
    const std::string out = fmt::format("m{}", n);
    ASSERT_EQ(Run("merge " + out + parts, &log), 0) << log;
    EXPECT_NE(log.find("3 factorizations (9 files) from " + std::to_string(n) + " folders"),
              std::string::npos)
        << log;
    EXPECT_TRUE(Folder(dir_ / out) == ref) << n << " shards: merged folder differs";
  }
  // Identical duplicates once; a changed file is a conflict naming both folders.
  ASSERT_EQ(Run("merge dup ref f2-0 f2-1", &log), 0) << log;
  EXPECT_NE(log.find("(9 identical files kept once)"), std::string::npos) << log;
  EXPECT_TRUE(Folder(dir_ / "dup") == ref);
  fs::copy(dir_ / "f2-0", dir_ / "bad");
  const std::string victim = Folder(dir_ / "bad").begin()->first;
  { std::ofstream(dir_ / "bad" / victim, std::ios::app) << " "; }
  EXPECT_EQ(Run("merge c ref bad", &log), 2);
  EXPECT_NE(log.find(victim + " differs between ref and bad"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir_ / "c"));
  EXPECT_TRUE(Folder(dir_ / "ref") == ref) << "merge modified a part";
  // A timed run differs only in what --no-timings leaves out: not byte-identical, refused.
  ASSERT_EQ(Run(Factor("-o timed"), &log), 0) << log;
  EXPECT_NE(ReadAll(dir_ / "timed" / "a_x.factor.json").find("\"seconds\""), std::string::npos);
  EXPECT_EQ(Run("merge c2 ref timed", &log), 2) << log;
}

TEST_F(ShardFactorBench, BenchShardsMergeToTheUnshardedCsvByteForByte) {
  std::string log;
  ASSERT_EQ(Run(Bench("--no-timings -o ref.csv"), &log), 0) << log;
  const std::string ref = ReadAll(dir_ / "ref.csv");
  // 3 tables x 2 budgets, by material key; the times written as 0.
  EXPECT_NE(ref.find("\na/x,lab/a/x.h5,"), std::string::npos) << ref;
  EXPECT_NE(ref.find("\nb/x,lab/b/x.h5,"), std::string::npos) << ref;
  EXPECT_LT(ref.find("\na/x,lab/a/x.h5,"), ref.find("\na/y,lab/a/y.h5,"));
  EXPECT_LT(ref.find("\na/y,lab/a/y.h5,"), ref.find("\nb/x,lab/b/x.h5,"));
  for (int n : {1, 2, 3}) {
    std::string parts;
    for (int i = 0; i < n; ++i) {
      const std::string part = fmt::format("b{}-{}.csv", n, i);
      ASSERT_EQ(Run(Bench("--no-timings --shard " + std::to_string(i) + "/" + std::to_string(n) +
                          " -o " + part),
                    &log),
                0)
          << log;
      parts += " " + part;
    }
    const std::string out = fmt::format("m{}.csv", n);
    ASSERT_EQ(Run("merge " + out + parts, &log), 0) << log;
    EXPECT_NE(log.find("6 bench rows from " + std::to_string(n) + " parts"), std::string::npos)
        << log;
    EXPECT_TRUE(ReadAll(dir_ / out) == ref) << n << " shards: merged CSV differs\n"
                                            << ReadAll(dir_ / out) << "\n---\n"
                                            << ref;
  }
  // A timed shard holds the same results: kept once with the untimed one; --no-timings zeroes.
  ASSERT_EQ(Run(Bench("--shard 0/2 -o timed.csv"), &log), 0) << log;
  ASSERT_EQ(Run("merge --no-timings mt.csv timed.csv ref.csv", &log), 0) << log;
  EXPECT_NE(log.find("6 bench rows from 2 parts"), std::string::npos) << log;
  EXPECT_TRUE(ReadAll(dir_ / "mt.csv") == ref);
  // A conflict: another log_rmse for one row of a part.
  std::vector<report::BenchPoint> rows = report::ReadBenchCsv(dir_ / "b2-1.csv");
  ASSERT_FALSE(rows.empty());
  rows[0].metrics.log_rmse = 2 * rows[0].metrics.log_rmse + 1e-3;
  report::WriteBenchCsv(dir_ / "bad.csv", rows);
  EXPECT_EQ(Run("merge c.csv ref.csv bad.csv", &log), 2);
  EXPECT_NE(log.find("conflicting bench rows of " + rows[0].material), std::string::npos) << log;
  EXPECT_NE(log.find("ref.csv and bad.csv"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir_ / "c.csv"));
  EXPECT_TRUE(ReadAll(dir_ / "ref.csv") == ref) << "merge modified a part";
  // Kinds are not mixed.
  EXPECT_EQ(Run("merge c.csv ref.csv ref", &log), 2) << log;
}

}  // namespace
}  // namespace brdfit
