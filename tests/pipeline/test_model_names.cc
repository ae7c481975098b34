// `brdfit fit --model` names (pipeline::ResolveModelNames): --diffuse reaches every bare
// specular name or is refused, never dropped; and the JSON parameters name the parameters that
// ended on a bound, as the HDF5 report's at_bound does (issue 15 item 5).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "core/error.h"
#include "fit/fitter.h"
#include "io/fit_report.h"
#include "io/table_io.h"
#include "models/registry.h"
#include "pipeline/batch_fit.h"
#include "pipeline/fit_settings.h"
#include "tests/fit/fit_test_util.h"
#include "tests/io/io_test_util.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using pipeline::ResolveModelNames;

TEST(ModelNames, EveryBareSpecularLobeGetsLambert) {
  int bare = 0;
  for (const std::string& m : FittableModels()) {
    if (m.find('+') != std::string::npos) continue;
    if (m == "lambert" || m == "oren-nayar" || m == "burley" || m == "oren-nayar-fujii" ||
        m == "burley-2012" || m == "ue4") {
      EXPECT_EQ(ResolveModelNames({m}, "lambert").front(), m)
          << "a diffuse body (or ue4, with its own) stays as given";
    } else if (IsFittable("lambert+" + m)) {
      ++bare;
      EXPECT_EQ(ResolveModelNames({m}, "lambert").front(), "lambert+" + m);
    } else {
      // ward-duer: no lambert+ward-duer in the catalog, so refused rather than fitted bare.
      EXPECT_THROW(ResolveModelNames({m}, "lambert"), InputError) << m;
      EXPECT_EQ(ResolveModelNames({m}, "none").front(), m);
    }
  }
  EXPECT_GE(bare, 11);
  EXPECT_EQ(ResolveModelNames({"ggx-hc"}, "lambert").front(), "lambert+ggx-hc");
  EXPECT_EQ(ResolveModelNames({"ggx:2"}, "lambert").front(), "lambert+ggx+ggx");
  EXPECT_EQ(ResolveModelNames({"ggx-hc"}, "none").front(), "ggx-hc");
  EXPECT_EQ(ResolveModelNames({"ggx"}, "burley").front(), "burley+ggx");
  EXPECT_EQ(ResolveModelNames({"lambert+ggx-hc"}, "burley").front(), "lambert+ggx-hc");
}

TEST(ModelNames, ADiffuseWithoutTheSumIsAClearError) {
  try {
    ResolveModelNames({"ggx-hc"}, "burley");
    FAIL() << "burley+ggx-hc is not in the catalog";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("burley+ggx-hc"), std::string::npos) << msg;
    EXPECT_NE(msg.find("--diffuse none"), std::string::npos) << msg;
  }
  EXPECT_THROW(ResolveModelNames({"ggx"}, "ggx-hc"), InputError);  // not a diffuse body
  EXPECT_THROW(ResolveModelNames({"ggx"}, "nonsense"), InputError);
}

TEST(ModelNames, JsonNamesTheParametersOnABound) {
  ScratchDir dir;
  // No blue diffuse and a white F0: lambert.kd_b ends on its lower bound 0, ggx-f0.f0_* on
  // their upper bound 1; the other parameters are inside.
  const std::vector<double> truth = testing::Params(
      "lambert+ggx-f0", {"lambert.kd_r=0.20", "lambert.kd_g=0.12", "lambert.kd_b=0",
                         "ggx-f0.f0_r=1", "ggx-f0.f0_g=1", "ggx-f0.f0_b=1", "ggx-f0.alpha=0.2"});
  const Table t = testing::SynthModel("lambert+ggx-f0", truth, testing::SmallGrid());
  const fs::path table = dir.path() / "t.h5", report = dir.path() / "fits.h5",
                 json = dir.path() / "fits.json";
  SaveTable(t, table);
  const auto r = testing_io::RunCli({"fit", table.string(), "--model", "lambert+ggx-f0", "-o",
                                     report.string(), "--json", json.string(), "--no-progress"},
                                    dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  nlohmann::json j;
  std::ifstream(json) >> j;
  ASSERT_EQ(j["fits"].size(), 1u);
  const auto& names = j["fits"][0]["at_bound"];
  ASSERT_TRUE(names.is_array());
  std::set<std::string> got;
  for (const auto& n : names) got.insert(n.get<std::string>());
  EXPECT_TRUE(got.count("lambert.kd_b")) << names.dump();
  EXPECT_FALSE(got.count("lambert.kd_r")) << names.dump();
  EXPECT_FALSE(got.count("ggx-f0.alpha")) << names.dump();
  // The same set as the HDF5 report's at_bound.
  const auto entries = ReadFitReport(report);
  ASSERT_EQ(entries.size(), 1u);
  std::set<std::string> h5;
  for (std::size_t i = 0; i < entries[0].result.at_bound.size(); ++i) {
    if (entries[0].result.at_bound[i]) h5.insert(entries[0].result.param_names[i]);
  }
  EXPECT_EQ(got, h5);
}

// One set of defaults: `brdfit fit` and Python turn FitSettings{} into the library's
// FitOptions{} (fit/options.h defines them once); of the samples, only the budget differs
// (the library's SampleOptions{} fits every cell, the CLI's default budget is a stride).
TEST(FitSettingsDefaults, AreTheLibrarysFitOptions) {
  SampleOptions samples;
  FitOptions fit = LogLossUnpolished();  // every default below must be set by the settings
  pipeline::ApplyFitSettings(pipeline::FitSettings{}, &samples, &fit);
  EXPECT_EQ(fit, FitOptions{});
  SampleOptions library;
  library.budget = DefaultFitBudget();
  EXPECT_EQ(OptionsJson(samples, fit), OptionsJson(library, FitOptions{}));
  EXPECT_EQ(FitOptions{}.loss, LossKind::kRel);
  EXPECT_EQ(FitOptions{}.polish, PolishKind::kRendered);
}

}  // namespace
}  // namespace brdfit
