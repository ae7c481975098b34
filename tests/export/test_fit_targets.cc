// `brdfit fit --target T` (export/fit_targets.h): the model each target is said to render
// exactly really exports exactly (the exporters' own check, the one test_export_formulas holds
// to the targets' documented BSDFs), the other masking does not, and what cannot be exported
// is said.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/error.h"
#include "export/fit_targets.h"
#include "models/registry.h"

namespace brdfit {
namespace {

FitResult Fit(const std::string& model, const std::vector<double>& params) {
  const ModelInfo* m = FindModel(model);
  EXPECT_NE(m, nullptr) << model;
  FitResult r;
  r.model = model;
  r.param_names = m->param_names;
  r.params = params;
  r.at_bound.assign(params.size(), false);
  r.status = FitStatus::kConverged;
  return r;
}

TEST(FitTargets, EachTargetsModelExportsExactlyAndTheOtherMaskingDoesNot) {
  const std::vector<double> grey = {0.30, 0.20, 0.10, 0.25, 0.25, 0.25, 0.15};
  for (const char* name : {"gltf", "blender", "mitsuba", "pbrt"}) {
    const exports::FitTarget& t = exports::FitTargetOf(name);
    ASSERT_GE(t.models.size(), 1u) << name;
    EXPECT_TRUE(exports::ExportFidelity(Fit(t.models[0], grey), t).Exact()) << name;
    const std::string other = t.models[0] == "lambert+ggx" ? "lambert+ggx-hc" : "lambert+ggx";
    const exports::Fidelity f = exports::ExportFidelity(Fit(other, grey), t);
    ASSERT_FALSE(f.Exact()) << name;
    EXPECT_NE(f.approximations[0].find("Smith G"), std::string::npos) << f.approximations[0];
  }
  // A coloured ks: exact where the target has a free RGB weight (Mitsuba, Blender's Glossy
  // colour), not where a Fresnel rises to white (glTF, pbrt).
  const std::vector<double> coloured = {0.05, 0.10, 0.30, 0.60, 0.35, 0.10, 0.2};
  for (const char* name : {"mitsuba", "blender"}) {
    const auto& t = exports::FitTargetOf(name);
    EXPECT_TRUE(exports::ExportFidelity(Fit(t.models[0], coloured), t).Exact()) << name;
  }
  for (const char* name : {"gltf", "pbrt"}) {
    const auto& t = exports::FitTargetOf(name);
    EXPECT_FALSE(exports::ExportFidelity(Fit(t.models[0], coloured), t).Exact()) << name;
  }
}

// Blender and Mitsuba 3 also fit two GGX lobes, which they express exactly (any RGB ks).
TEST(FitTargets, BlenderAndMitsubaFitTwoLobesExactly) {
  const std::vector<double> two = {0.20, 0.12, 0.05, 0.05, 0.04, 0.03,
                                   0.30, 0.50, 0.40, 0.35, 0.02};
  for (const char* name : {"blender", "mitsuba"}) {
    const exports::FitTarget& t = exports::FitTargetOf(name);
    ASSERT_GE(t.models.size(), 2u) << name;
    ASSERT_EQ(t.models[1], "lambert+ggx+ggx") << name;
    EXPECT_TRUE(exports::ExportFidelity(Fit(t.models[1], two), t).Exact()) << name;
  }
  for (const char* name : {"gltf", "pbrt"}) {
    const exports::Fidelity f =
        exports::ExportFidelity(Fit("lambert+ggx+ggx", two), exports::FitTargetOf(name));
    EXPECT_FALSE(f.Exact()) << name;
  }
}

// Blender also fits the rough bodies its Diffuse and Principled BSDFs evaluate, exactly;
// Mitsuba 3 the one its principled BSDF evaluates (Burley 2012), not Fujii's Oren-Nayar, which
// it has no plugin for.
TEST(FitTargets, BlenderFitsRoughBodiesExactly) {
  const exports::FitTarget& t = exports::FitTargetOf("blender");
  const exports::FitTarget& mitsuba = exports::FitTargetOf("mitsuba");
  const std::vector<double> p = {0.4, 0.3, 0.2, 0.7, 0.05, 0.05, 0.05, 0.1};
  for (const char* model : {"oren-nayar-fujii+ggx", "burley-2012+ggx"}) {
    EXPECT_NE(std::find(t.models.begin(), t.models.end(), model), t.models.end()) << model;
    EXPECT_TRUE(exports::ExportFidelity(Fit(model, p), t).Exact()) << model;
  }
  EXPECT_FALSE(exports::ExportFidelity(Fit("oren-nayar-fujii+ggx", p), mitsuba).Exact());
  EXPECT_EQ(std::find(mitsuba.models.begin(), mitsuba.models.end(), "oren-nayar-fujii+ggx"),
            mitsuba.models.end());
  EXPECT_TRUE(exports::ExportFidelity(Fit("burley-2012+ggx", p), mitsuba).Exact());
  EXPECT_NE(std::find(mitsuba.models.begin(), mitsuba.models.end(), "burley-2012+ggx"),
            mitsuba.models.end());
  // brdfit's other rough bodies (qualitative Oren-Nayar, Frostbite's Burley) are not Cycles'.
  for (const char* model : {"oren-nayar+ggx", "burley+ggx"}) {
    EXPECT_FALSE(exports::ExportFidelity(Fit(model, p), t).Exact()) << model;
  }
}

TEST(FitTargets, ThreejsTakesAnyModelAndOthersSayWhatTheyCannotTake) {
  const exports::FitTarget& three = exports::FitTargetOf("threejs");
  EXPECT_TRUE(three.models.empty());
  const ModelInfo* ward = FindModel("lambert+ward");
  ASSERT_NE(ward, nullptr);
  const FitResult w = Fit("lambert+ward", std::vector<double>(ward->params.size(), 0.1));
  EXPECT_TRUE(exports::ExportFidelity(w, three).Exact());
  const exports::Fidelity f = exports::ExportFidelity(w, exports::FitTargetOf("gltf"));
  ASSERT_EQ(f.approximations.size(), 1u);
  EXPECT_NE(f.approximations[0].find("lambert+ggx-hc"), std::string::npos);
  EXPECT_NE(f.approximations[0].find("lambert+ward"), std::string::npos);
  try {
    exports::FitTargetOf("unity");
    FAIL() << "unity accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("gltf, threejs, blender, mitsuba, pbrt"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace brdfit
