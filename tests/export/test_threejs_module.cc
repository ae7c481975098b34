// The three.js module's pieces that the render test cannot isolate: the half-float encoding
// (IEEE 754 binary16 bit patterns as the standard tabulates them), the JS escaping of the
// GLSL, and which textures a factorization's module declares.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "export/threejs_module.h"

namespace brdfit {
namespace {

using exports::ToHalf;

TEST(ThreejsModule, HalfFloatBitPatterns) {
  bool clipped = false;
  EXPECT_EQ(ToHalf(0.0f, &clipped), 0x0000);
  EXPECT_EQ(ToHalf(-0.0f, &clipped), 0x8000);
  EXPECT_EQ(ToHalf(1.0f, &clipped), 0x3c00);
  EXPECT_EQ(ToHalf(-2.0f, &clipped), 0xc000);
  EXPECT_EQ(ToHalf(0.5f, &clipped), 0x3800);
  EXPECT_EQ(ToHalf(0.1f, &clipped), 0x2e66);                     // 0.0999755859375
  EXPECT_EQ(ToHalf(65504.0f, &clipped), 0x7bff);                 // the largest half
  EXPECT_EQ(ToHalf(6.103515625e-05f, &clipped), 0x0400);         // the smallest normal, 2^-14
  EXPECT_EQ(ToHalf(5.9604644775390625e-08f, &clipped), 0x0001);  // the smallest subnormal
  EXPECT_EQ(ToHalf(1.0f + 1.0f / 2048, &clipped), 0x3c00);       // halfway: to even (down)
  EXPECT_EQ(ToHalf(1.0f + 3.0f / 2048, &clipped), 0x3c02);       // halfway: to even (up)
  EXPECT_FALSE(clipped);
  EXPECT_EQ(ToHalf(1e6f, &clipped), 0x7bff);
  EXPECT_TRUE(clipped);
  clipped = false;
  EXPECT_EQ(ToHalf(-std::numeric_limits<float>::infinity(), &clipped), 0xfbff);
  EXPECT_TRUE(clipped);
}

exports::Provenance Prov() {
  exports::Provenance p;
  p.version = "0.1.0";
  p.source = "synthetic";
  p.material = "m`${x}";
  p.model = "lambert+ggx";
  p.metrics = "none";
  p.target = "three.js";
  return p;
}

TEST(ThreejsModule, AnalyticModuleCarriesTheParamsAndEscapesTheGlsl) {
  const exports::ThreejsAnalytic a{"lambert+ggx",
                                   {0.5, 0.25, 0.125, 0.04, 0.04, 0.04, 0.1},
                                   "// a `tick` and ${not_js} and \\\\ in GLSL\nvec3 EvalBrdf"};
  const std::string js = exports::ThreejsModule(a, Prov());
  EXPECT_NE(js.find("params: [0.5, 0.25, 0.125, 0.04, 0.04, 0.04, 0.1]"), std::string::npos);
  EXPECT_NE(js.find("a \\`tick\\` and \\${not_js} and \\\\\\\\ in GLSL"), std::string::npos);
  EXPECT_NE(js.find("material: \"m`${x}\""), std::string::npos);  // a JS string, not a template
  EXPECT_NE(js.find("uParams: { value: brdfit.params.slice() }"), std::string::npos);
  EXPECT_NE(js.find("export default function createMaterial()"), std::string::npos);
}

TEST(ThreejsModule, FactoredModuleDeclaresEveryTermsTextures) {
  exports::ThreejsFactored f;
  f.parameterization = "halfdiff";
  f.diffuse = {0.1, 0.2, 0.3};
  for (int k = 0; k < 2; ++k) {
    f.p.push_back(RgbImage::Filled(2, 2, 1.0f));
    f.q.push_back(RgbImage::Filled(4, 2, 1e6f));  // clipped to 65504
  }
  f.brdf_glsl = "vec3 EvalBrdf";
  exports::Fidelity fid;
  const std::string js = exports::ThreejsFactoredModule(f, Prov(), &fid);
  for (const char* name : {"uFactorP", "uFactorQ", "uFactorP2", "uFactorQ2"}) {
    EXPECT_NE(js.find(std::string(name) + ": { value: halfTexture(...textures." + name + ") }"),
              std::string::npos)
        << name;
  }
  EXPECT_EQ(js.find("uFactorP3"), std::string::npos);
  // 2 x 2 RGBA halves of 1.0: 00 3c 00 3c 00 3c 00 3c, four times, in base64.
  EXPECT_NE(js.find("uFactorP: [\"ADwAPAA8ADwAPAA8ADwAPAA8ADwAPAA8ADwAPAA8ADw=\", 2, 2, false]"),
            std::string::npos);
  EXPECT_NE(js.find(", 4, 2, true]"), std::string::npos);  // halfdiff's q repeats in its rows
  ASSERT_EQ(fid.approximations.size(), 1u);
  EXPECT_NE(fid.approximations[0].find("65504"), std::string::npos);
}

// Names reach the module's header comment and its provenance object: neither may end early.
// The comment holds printable ASCII only ('?' for the rest); the strings escape every character
// outside printable ASCII, and bytes that are not UTF-8 become U+FFFD.
TEST(ThreejsModule, NamesCannotLeaveTheirCommentOrString) {
  exports::Provenance p = Prov();
  p.material = "paint\nconsole.log('INJECTED');//\r\xe2\x80\xa8x";
  p.source = std::string("caf\xc3\xa9 \xf0\x9f\x8e\xa8 \xff\xc0\xaf nul\0", 19) + "\"\\";
  const exports::ThreejsAnalytic a{"lambert+ggx", {0.5, 0.5, 0.5, 0.04, 0.04, 0.04, 0.1}, "x"};
  const std::string js = exports::ThreejsModule(a, p);
  // Every line that holds the payload is a comment, or the provenance object's string.
  std::size_t at = 0;
  while ((at = js.find("console.log", at)) != std::string::npos) {
    const std::size_t line = js.rfind('\n', at) + 1;
    const std::string text = js.substr(line, js.find('\n', at) - line);
    EXPECT_TRUE(text.starts_with("// ") || text.starts_with("  material: \"")) << text;
    ++at;
  }
  EXPECT_NE(js.find("(material paint?console.log('INJECTED');//????x)"), std::string::npos);
  EXPECT_NE(js.find("material: \"paint\\u000aconsole.log('INJECTED');//\\u000d\\u2028x\""),
            std::string::npos);
  EXPECT_NE(
      js.find("source: \"caf\\u00e9 \\ud83c\\udfa8 \\ufffd\\ufffd\\ufffd nul\\u0000\\\"\\\\\""),
      std::string::npos)
      << js.substr(js.find("source: "), 80);
  for (const char c : js) {  // printable ASCII and newlines only
    EXPECT_TRUE(c == '\n' || (c >= 0x20 && c < 0x7f)) << static_cast<int>(c);
  }
}

}  // namespace
}  // namespace brdfit
