// Material identity (issue 17 item 5, pipeline/material_keys.h): a/x.binary and b/x.binary are
// two materials, "a/x" and "b/x"; one folder's tables keep their stems; the keys do not depend
// on the working directory or where the tables are mounted. Through the CLI: both fit into one
// report as two materials (each with its own choice), and sharded + merged equals unsharded.
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/synth.h"
#include "io/fit_report.h"
#include "io/hdf5_table.h"
#include "models/registry.h"
#include "pipeline/material_keys.h"
#include "tests/pipeline/lab_tables.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using pipeline::MaterialKeys;
using Keys = std::vector<std::string>;

TEST(MaterialKeys, OneFolderKeepsTheStems) {
  EXPECT_EQ(MaterialKeys({"data/gold-paint.binary"}), Keys{"gold-paint"});
  EXPECT_EQ(MaterialKeys({"/x/m/a.binary", "/x/m/b.h5", "nbrdf:alum-bronze"}),
            (Keys{"a", "b", "alum-bronze"}));
}

TEST(MaterialKeys, SameStemInTwoFoldersIsTwoMaterials) {
  EXPECT_EQ(MaterialKeys({"lab/a/x.binary", "lab/b/x.binary"}), (Keys{"a/x", "b/x"}));
  EXPECT_EQ(MaterialKeys({"/d/a/x.binary", "/d/a/deep/y.h5", "/d/c.h5"}),
            (Keys{"a/x", "a/deep/y", "c"}));
  // Written differently, the same paths: lexically normal.
  EXPECT_EQ(MaterialKeys({"/d/./a/x.binary", "/d/b/../b/x.binary"}), (Keys{"a/x", "b/x"}));
}

TEST(MaterialKeys, DoNotDependOnTheMountPointOrTheWorkingDirectory) {
  EXPECT_EQ(MaterialKeys({"/data/brdf/a/x.binary", "/data/brdf/b/x.binary"}),
            MaterialKeys({"/mnt/b/a/x.binary", "/mnt/b/b/x.binary"}));
  const fs::path cwd = fs::current_path();
  EXPECT_EQ(MaterialKeys({"a/x.binary", "b/y.binary"}),
            MaterialKeys({(cwd / "a/x.binary").string(), (cwd / "b/y.binary").string()}));
}

TEST(MaterialKeys, StemsThatStillCollideKeepTheExtension) {
  EXPECT_EQ(MaterialKeys({"m/x.binary", "m/x.h5", "m/y.h5"}), (Keys{"x.binary", "x.h5", "y"}));
  EXPECT_EQ(MaterialKeys({"m/gold.binary", "nbrdf:gold"}), (Keys{"gold.binary", "gold"}));
}

TEST(MaterialKeys, TheSameTableTwiceIsRefusedNamingBoth) {
  try {
    MaterialKeys({"m/x.binary", "m/../m/x.binary"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("m/x.binary and m/../m/x.binary"), std::string::npos) << what;
  }
  EXPECT_THROW(MaterialKeys({"nbrdf:gold", "nbrdf:gold"}), InputError);
}

using testing::ReadAll;

class MaterialKeyCli : public testing::LabTables {
 protected:
  void SetUp() override { MakeTables("keys", {0.3, 0.25, 0.2, 0.4, 0.4, 0.4}, 0.08, 0.15, 1); }
  static std::string Fit(const std::string& extra) {
    return "fit lab/a/x.h5 lab/b/x.h5 lab/a/y.h5 --model ggx,ward --budget full --no-timings "
           "--no-progress -q " +
           extra;
  }
};

TEST_F(MaterialKeyCli, SameStemInTwoFoldersFitsAsTwoMaterialsAndShardsMerge) {
  std::string log;
  ASSERT_EQ(Run(Fit("-o ref.h5"), &log), 0) << log;
  const std::vector<FitReportEntry> ref = ReadFitReport(dir_ / "ref.h5");
  ASSERT_EQ(ref.size(), 6u);
  std::set<std::string> materials, chosen;
  for (const FitReportEntry& e : ref) {
    materials.insert(e.material);
    if (e.chosen) chosen.insert(e.material);
  }
  EXPECT_EQ(materials, (std::set<std::string>{"a/x", "b/x", "a/y"}));
  EXPECT_EQ(chosen, materials) << "one chosen fit per material";
  // The two x tables' fits differ (other content), and name their own sources.
  for (const FitReportEntry& e : ref) {
    EXPECT_EQ(e.source, "lab/" + e.material + ".h5");
  }
  const std::string ref_bytes = ReadAll(dir_ / "ref.h5");
  for (int n : {2, 3}) {
    std::string parts;
    for (int i = 0; i < n; ++i) {
      const std::string part = fmt::format("s{}-{}.h5", n, i);
      ASSERT_EQ(
          Run(Fit("--shard " + std::to_string(i) + "/" + std::to_string(n) + " -o " + part), &log),
          0)
          << log;
      parts += " " + part;
    }
    ASSERT_EQ(Run(fmt::format("merge m{}.h5", n) + parts, &log), 0) << log;
    EXPECT_TRUE(ReadAll(dir_ / fmt::format("m{}.h5", n)) == ref_bytes) << n << " shards";
  }
}

// A report holds one source per material key: b/x.h5 alone is "x", as a/x.h5 alone was.
TEST_F(MaterialKeyCli, ASecondTableUnderAKeptKeyIsRefusedNotMistakenForIt) {
  std::string log;
  ASSERT_EQ(Run("fit lab/a/x.h5 --model ggx --no-timings --no-progress -q -o r.h5", &log), 0)
      << log;
  const std::string before = ReadAll(dir_ / "r.h5");
  EXPECT_EQ(Run("fit lab/b/x.h5 --model ggx --no-timings --no-progress -q -o r.h5", &log), 2);
  EXPECT_NE(log.find("material 'x' fitted from lab/a/x.h5"), std::string::npos) << log;
  EXPECT_TRUE(ReadAll(dir_ / "r.h5") == before) << "the report was changed";
  // Their separate reports do not merge into one material either.
  ASSERT_EQ(Run("fit lab/b/x.h5 --model ggx --no-timings --no-progress -q -o r2.h5", &log), 0)
      << log;
  EXPECT_EQ(Run("merge m.h5 r.h5 r2.h5", &log), 2);
  EXPECT_NE(log.find("material 'x' is lab/a/x.h5 in r.h5 but lab/b/x.h5 in r2.h5"),
            std::string::npos)
      << log;
  EXPECT_FALSE(fs::exists(dir_ / "m.h5"));
}

}  // namespace
}  // namespace brdfit
