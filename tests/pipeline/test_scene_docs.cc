// The example scene of docs/scenes.md, as printed there, loads: its fit report material takes
// the fit's parameters and its sidecar material the factorization (issue 14 item 16: the
// example named "fits.json", which is not a fit report, and `factors` was read as a prefix).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/synth.h"
#include "factor/factor.h"
#include "io/fit_report.h"
#include "models/registry.h"
#include "pipeline/factor_export.h"
#include "pipeline/material_loader.h"
#include "preview/scene.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;

// The first ```json block of docs/scenes.md.
std::string DocumentedScene() {
  std::ifstream in(fs::path(BRDFIT_SOURCE_DIR) / "docs" / "scenes.md");
  const std::string doc(std::istreambuf_iterator<char>(in), {});
  const std::size_t begin = doc.find("```json\n");
  const std::size_t end = doc.find("```", begin + 8);
  if (begin == std::string::npos || end == std::string::npos) return "";
  return doc.substr(begin + 8, end - begin - 8);
}

TEST(SceneDocs, TheExampleLoadsItsFitReportAndItsSidecar) {
  const std::string text = DocumentedScene();
  ASSERT_NE(text.find("\"fit_report\": \"fits.h5\""), std::string::npos) << text;
  ScratchDir dir;
  std::ofstream(dir / "scene.json") << text;

  // What the example names: fits.h5 (brdfit fit felt.binary --model ggx -o fits.h5) and
  // fac/felt.factor.json (brdfit factor felt.binary -o fac), from a small lambert+ggx table.
  const ModelInfo* m = FindModel("lambert+ggx");
  std::vector<double> p = m->DefaultParams();
  p[0] = 0.42;
  const Table t = SynthesizeTable(
      Grid{16, 16, 32, ThetaHMapping::kSqrt},
      [&](const Geometry& g, double rgb[3]) { m->eval(p.data(), g, rgb); }, {});
  FitReportEntry e;
  e.source = (dir / "felt.binary").string();
  e.material = "felt";
  e.options = "{}";
  e.result.model = m->name;
  e.result.param_names = m->param_names;
  e.result.params = p;
  e.result.at_bound.assign(p.size(), false);
  e.result.status = FitStatus::kConverged;
  e.result.metrics.ok = true;
  WriteFitReport({e}, dir / "fits.h5");
  FactorOptions fo;
  fo.resolution = 8;
  fs::create_directories(dir / "fac");
  SaveFactorization(Factor(t, fo), dir / "fac", "felt");

  const preview::Scene scene = preview::LoadScene(dir / "scene.json");
  pipeline::LoadOptions lo;
  lo.cache_dir = dir / "cache";
  const preview::MaterialSet set =
      pipeline::LoadMaterials(scene, {"felt-fit", "felt-sidecar"}, lo, nullptr);
  ASSERT_EQ(set.count("felt-fit"), 1u);
  EXPECT_EQ(set.at("felt-fit").params, p);
  ASSERT_EQ(set.count("felt-sidecar"), 1u);
  EXPECT_NE(set.at("felt-sidecar").factors, nullptr);
}

}  // namespace
}  // namespace brdfit
