// The GLSL side of every catalog model cannot drift from its C++ kParams: each lobe's parameter
// block is generated from kParams (names, count, order), the twins hold no layout of their own
// and read every parameter by name, EvalBrdf hands each lobe its slice of uParams, and every
// model's shader compiles (a twin reading a parameter kParams does not have fails here).
#include <gtest/gtest.h>

#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/catalog.h"
#include "preview/gl_objects.h"
#include "preview/glsl_models.h"
#include "preview/glsl_params.h"
#include "preview/glsl_sources.h"
#include "preview/shader_gen.h"
#include "tests/preview/gl_test_env.h"

namespace brdfit::preview {
namespace {

// The field names of "struct <name> { float a; float b; ... };" in order.
std::vector<std::string> StructFields(const std::string& block, const std::string& name) {
  EXPECT_EQ(block.rfind("struct " + name + " {\n", 0), 0u) << block;
  std::vector<std::string> fields;
  const std::regex field(R"(\n  float (\w+);)");
  for (std::sregex_iterator it(block.begin(), block.end(), field), end; it != end; ++it) {
    fields.push_back((*it)[1]);
  }
  return fields;
}

// The GLSL that evaluates a lobe: its generated entry point, else its twin file.
std::string Evaluation(const GlslLobe& lobe) {
  return lobe.entry_point.empty() ? std::string(GlslSource(lobe.file)) : lobe.entry_point;
}

template <class M>
void CheckLobe(const GlslLobe& lobe) {
  SCOPED_TRACE(lobe.name);
  ASSERT_EQ(lobe.name, M::kName);
  ASSERT_EQ(lobe.count, kNumParams<M>);
  std::vector<std::string> want;
  for (const ParamSpec& p : M::kParams) want.emplace_back(p.name);
  EXPECT_EQ(lobe.param_names, want);
  EXPECT_EQ(StructFields(lobe.param_block, lobe.params_struct), want);

  const std::string eval = Evaluation(lobe);
  const std::string sig =
      "vec3 " + lobe.function + "(const in " + lobe.params_struct + " p, const in BrdfGeometry g)";
  EXPECT_NE(eval.find(sig), std::string::npos) << "expected the entry point '" << sig << "'";
  // Every parameter is read, by name: a parameter added to kParams and ignored by the GLSL fails.
  for (const std::string& name : want) {
    EXPECT_TRUE(std::regex_search(eval, std::regex("\\bp\\." + name + "\\b")))
        << lobe.file << " never reads p." << name;
  }
}

template <class M>
struct Lobes {
  static void Check(const std::vector<GlslLobe>& lobes) {
    ASSERT_EQ(lobes.size(), 1u);
    CheckLobe<M>(lobes[0]);
  }
};
template <class... L>
struct Lobes<Sum<L...>> {
  static void Check(const std::vector<GlslLobe>& lobes) {
    ASSERT_EQ(lobes.size(), sizeof...(L));
    std::size_t i = 0;
    (CheckLobe<L>(lobes[i++]), ...);
  }
};

TEST(GlslTwins, ParameterBlocksAreGeneratedFromKParams) {
  int models = 0;
  ForEachModel([&](auto m) {
    using M = typename decltype(m)::type;
    SCOPED_TRACE(ModelName<M>());
    Lobes<M>::Check(GlslLobes(ModelName<M>()));
    ++models;
  });
  EXPECT_GT(models, 0);
}

// The GLSL files restate no parameter layout: no arrays of parameters, no hand-written
// parameter structs, no comment tables, no uParams indices.
TEST(GlslTwins, TwinsHoldOnlyTheirEvaluation) {
  int files = 0;
  for (const GlslFile& f : EmbeddedGlsl()) {
    if (f.path.rfind("models/glsl/", 0) != 0) continue;
    SCOPED_TRACE(std::string(f.path));
    const std::string text(f.text);
    EXPECT_EQ(text.find("float p["), std::string::npos);
    EXPECT_FALSE(std::regex_search(text, std::regex(R"(struct\s+brdfit_\w*_params)")));
    EXPECT_EQ(text.find("brdfit-params"), std::string::npos);
    EXPECT_EQ(text.find("uParams"), std::string::npos);
    EXPECT_FALSE(std::regex_search(text, std::regex(R"(\bp\[\d+\])")));
    ++files;
  }
  EXPECT_GT(files, 0);
}

// EvalBrdf: one uParams array of the model's length, each lobe built from its own slice.
TEST(GlslTwins, EvalBrdfPassesEachLobeItsSlice) {
  ForEachModel([&](auto m) {
    using M = typename decltype(m)::type;
    SCOPED_TRACE(ModelName<M>());
    ShaderVariant v;
    v.model = ModelName<M>();
    v.num_directional = 1;
    const std::string src = ShadeFragmentSource(v);
    EXPECT_NE(src.find("uniform float uParams[" + std::to_string(kNumParams<M>) + "];"),
              std::string::npos);
    for (const GlslLobe& lobe : GlslLobes(ModelName<M>())) {
      const std::string call = lobe.function + "(" +
                               GlslParamConstructor(lobe.name, "uParams", lobe.offset, lobe.count) +
                               ", g)";
      EXPECT_NE(src.find(call), std::string::npos) << "expected '" << call << "'";
    }
  });
}

TEST(GlslTwins, CompositeLobesTileTheParameterVector) {
  const auto lobes = GlslLobes("lambert+ggx");
  ASSERT_EQ(lobes.size(), 2u);
  EXPECT_EQ(lobes[0].function, "brdfit_lambert");
  EXPECT_EQ(lobes[1].offset, 3u);
  EXPECT_EQ(lobes[1].count, 4u);
  EXPECT_EQ(GlslParamConstructor("ggx", "uParams", 3, 2),
            "brdfit_ggx_params(uParams[3], uParams[4])");
  EXPECT_EQ(GlslFunctionName("ggx-hc"), "brdfit_ggx_hc");
  EXPECT_EQ(GlslParamStructName("ggx-hc"), "brdfit_ggx_hc_params");
  EXPECT_THROW(GlslParamStruct("x", {{"not-glsl", "1", 0, 1, 0, false, "doc"}}),
               std::invalid_argument);
}

// The shader of every model compiles and links; and a twin that reads a parameter under a name
// kParams does not have is a compile error, not a silent zero.
TEST(GlslTwins, EveryModelShaderCompiles) {
  BRDFIT_REQUIRE_GL();
  ShaderVariant v;
  v.num_directional = 1;
  ForEachModel([&](auto m) {
    v.model = ModelName<typename decltype(m)::type>();
    EXPECT_NO_THROW(Program(ShadeVertexSource(v), ShadeFragmentSource(v))) << v.model;
  });
  v.model = "ggx";
  std::string wrong = ShadeFragmentSource(v);
  const std::size_t at = wrong.find("p.alpha");
  ASSERT_NE(at, std::string::npos);
  wrong.replace(at, 7, "p.roughness");
  try {
    Program(ShadeVertexSource(v), wrong);
    ADD_FAILURE() << "a twin reading p.roughness compiled";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("roughness"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace brdfit::preview
