// Every GLSL twin's parameter block (models/glsl/<name>.glsl, "brdfit-params") matches the
// C++ model's kParams: names, units, bounds, defaults, scale and role, in order. And every
// lobe of every catalog model has a twin whose function takes exactly that many parameters.
#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "models/catalog.h"
#include "preview/glsl_models.h"
#include "preview/glsl_sources.h"

namespace brdfit::preview {
namespace {

struct BlockRow {
  std::string name, unit, scale, role;
  double lower, upper, init;
};

// Parses "/* brdfit-params <model>\n header\n rows... */".
std::vector<BlockRow> ParseBlock(std::string_view text, const std::string& model) {
  const std::string tag = "/* brdfit-params " + model + "\n";
  const auto start = text.find(tag);
  EXPECT_NE(start, std::string_view::npos) << "no parameter block for " << model;
  if (start == std::string_view::npos) return {};
  const auto end = text.find("*/", start);
  std::istringstream in(std::string(text.substr(start + tag.size(), end - start - tag.size())));
  std::string line;
  std::getline(in, line);  // header
  std::vector<BlockRow> rows;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    BlockRow r;
    std::string lo, up, init;
    if (!(ls >> r.name >> r.unit >> lo >> up >> init >> r.scale >> r.role)) continue;
    r.lower = std::strtod(lo.c_str(), nullptr);
    r.upper = std::strtod(up.c_str(), nullptr);
    r.init = std::strtod(init.c_str(), nullptr);
    rows.push_back(r);
  }
  return rows;
}

std::string RoleName(ParamRole r) {
  switch (r) {
    case ParamRole::kShape: return "shape";
    case ParamRole::kWeightR: return "weight_r";
    case ParamRole::kWeightG: return "weight_g";
    case ParamRole::kWeightB: return "weight_b";
  }
  return "?";
}

template <class M>
void CheckLobe() {
  const std::string name(M::kName);
  SCOPED_TRACE(name);
  const std::string file = "models/glsl/" + name + ".glsl";
  std::string_view text;
  ASSERT_NO_THROW(text = GlslSource(file)) << "missing GLSL twin " << file;
  const auto rows = ParseBlock(text, name);
  ASSERT_EQ(rows.size(), M::kParams.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ParamSpec& s = M::kParams[i];
    EXPECT_EQ(rows[i].name, s.name);
    EXPECT_EQ(rows[i].unit, s.unit);
    EXPECT_DOUBLE_EQ(rows[i].lower, s.lower) << s.name;
    EXPECT_DOUBLE_EQ(rows[i].upper, s.upper) << s.name;
    EXPECT_DOUBLE_EQ(rows[i].init, s.init) << s.name;
    EXPECT_EQ(rows[i].scale, s.log_scale ? "log" : "linear") << s.name;
    EXPECT_EQ(rows[i].role, RoleName(s.role)) << s.name;
  }
  // The entry point takes exactly N parameters.
  const std::string sig = "vec3 " + GlslFunctionName(name) + "(const in float p[" +
                          std::to_string(M::kParams.size()) + "]";
  EXPECT_NE(text.find(sig), std::string_view::npos) << "expected '" << sig << "'";
}

template <class M>
struct Lobes {
  static void Check() { CheckLobe<M>(); }
};
template <class... L>
struct Lobes<Sum<L...>> {
  static void Check() { (CheckLobe<L>(), ...); }
};

TEST(GlslTwins, ParameterBlocksMatchCppTables) {
  int models = 0;
  ForEachModel([&](auto m) {
    Lobes<typename decltype(m)::type>::Check();
    ++models;
  });
  EXPECT_GT(models, 0);
}

TEST(GlslTwins, CompositeLobesTileTheParameterVector) {
  const auto lobes = GlslLobes("lambert+ggx");
  ASSERT_EQ(lobes.size(), 2u);
  EXPECT_EQ(lobes[0].function, "brdfit_lambert");
  EXPECT_EQ(lobes[1].offset, 3u);
  EXPECT_EQ(lobes[1].count, 4u);
  EXPECT_EQ(GlslFunctionName("ggx-hc"), "brdfit_ggx_hc");
}

}  // namespace
}  // namespace brdfit::preview
