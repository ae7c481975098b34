#include "export/threejs_module.h"

#include <fmt/core.h>

#include <cmath>
#include <cstring>

#include "export/comment_text.h"

namespace brdfit::exports {

namespace {

// Text inside a JS template literal: no backslash escapes, backticks or ${ substitutions.
std::string TemplateLiteral(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\\' || s[i] == '`' || (s[i] == '$' && i + 1 < s.size() && s[i + 1] == '{')) {
      out += '\\';
    }
    out += s[i];
  }
  return out;
}

// Decodes one UTF-8 sequence (RFC 3629, section 4: no overlongs, surrogates or code points
// past U+10FFFF) at s[i]; returns its length, or 0 if the bytes there are not one.
std::size_t Utf8Sequence(const std::string& s, std::size_t i, std::uint32_t* cp) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[i + k]); };
  const unsigned char c = b(0);
  std::size_t n = c < 0x80           ? 1
                  : (c >> 5) == 0x6  ? 2
                  : (c >> 4) == 0xe  ? 3
                  : (c >> 3) == 0x1e ? 4
                                     : 0;
  if (n == 0 || i + n > s.size()) return 0;
  std::uint32_t v = n == 1 ? c : c & (0x7f >> n);
  for (std::size_t k = 1; k < n; ++k) {
    if ((b(k) & 0xc0) != 0x80) return 0;
    v = (v << 6) | (b(k) & 0x3f);
  }
  static constexpr std::uint32_t kMin[] = {0, 0, 0x80, 0x800, 0x10000};
  if (v < kMin[n] || v > 0x10ffff || (v >= 0xd800 && v <= 0xdfff)) return 0;
  *cp = v;
  return n;
}

// A JS string literal in printable ASCII: quotes and backslashes escaped, every other character
// outside printable ASCII as \uXXXX (a surrogate pair past U+FFFF), so no line terminator
// (U+2028 and U+2029 included) or control character stands in the module's text. A byte that
// is not valid UTF-8 becomes U+FFFD, the replacement character: visibly not the original.
std::string JsString(const std::string& s) {
  std::string out = "\"";
  for (std::size_t i = 0; i < s.size();) {
    std::uint32_t cp = 0xfffd;
    const std::size_t n = Utf8Sequence(s, i, &cp);
    i += n == 0 ? 1 : n;
    if (cp == '"' || cp == '\\') {
      out += '\\';
      out += static_cast<char>(cp);
    } else if (cp >= 0x20 && cp < 0x7f) {
      out += static_cast<char>(cp);
    } else if (cp < 0x10000) {
      out += fmt::format("\\u{:04x}", cp);
    } else {
      const std::uint32_t v = cp - 0x10000;
      out += fmt::format("\\u{:04x}\\u{:04x}", 0xd800 + (v >> 10), 0xdc00 + (v & 0x3ff));
    }
  }
  return out + "\"";
}

// three.js compiles ShaderMaterials as GLSL ES 3.00 on WebGL 2 (its prefix: #version 300 es,
// varying -> in/out, gl_FragColor -> its output) and declares position, normal and the
// matrices. View space like preview/glsl/object.vert.
constexpr const char* kVertex = R"GLSL(
varying vec3 vViewPosition;  // surface -> camera, view space
varying vec3 vNormal;
void main() {
  vec4 mvPosition = modelViewMatrix * vec4(position, 1.0);
  vViewPosition = -mvPosition.xyz;
  vNormal = normalize(normalMatrix * normal);
  gl_Position = projectionMatrix * mvPosition;
}
)GLSL";

// After the BRDF code: three.js's directional lights (lights: true; colour = colour * intensity,
// direction towards the light in view space, no pi: its physical lights), the radiance
// sum_lights cos_i E f_r(wi, wo) in the local frame, and three.js's output colour space.
constexpr const char* kFragmentMain = R"GLSL(
varying vec3 vViewPosition;
varying vec3 vNormal;
#if NUM_DIR_LIGHTS > 0
uniform DirectionalLight directionalLights[NUM_DIR_LIGHTS];
#endif
void main() {
  vec3 n = normalize(vNormal), t, b;
  BuildFrame(n, t, b);
  vec3 v = normalize(vViewPosition);
  vec3 wo = vec3(dot(v, t), dot(v, b), dot(v, n));
  vec3 radiance = vec3(0.0);
#if NUM_DIR_LIGHTS > 0
  if (wo.z > 0.0) {
    for (int i = 0; i < NUM_DIR_LIGHTS; ++i) {
      vec3 l = directionalLights[i].direction;
      vec3 wi = vec3(dot(l, t), dot(l, b), dot(l, n));
      if (wi.z > 0.0) {
        radiance += wi.z * directionalLights[i].color * EvalBrdf(MakeBrdfGeometry(wi, wo));
      }
    }
  }
#endif
  gl_FragColor = vec4(radiance, 1.0);
  #include <colorspace_fragment>
}
)GLSL";

}  // namespace

std::uint16_t ToHalf(float f, bool* clipped) {
  std::uint32_t x = 0;
  std::memcpy(&x, &f, sizeof x);
  const std::uint16_t sign = static_cast<std::uint16_t>((x >> 16) & 0x8000u);
  const float a = std::fabs(f);
  if (!(a < 65520.0f)) {  // rounds beyond 65504 (or NaN): clip to the largest half
    *clipped = true;
    return static_cast<std::uint16_t>(sign | 0x7bffu);
  }
  if (a < 6.103515625e-05f) {  // below 2^-14: subnormal, m 2^-24 (m = 1024 is 2^-14, normal)
    return static_cast<std::uint16_t>(sign |
                                      static_cast<std::uint16_t>(std::nearbyint(a * 16777216.0f)));
  }
  const std::uint32_t ax = x & 0x7fffffffu, mant = ax & 0x7fffffu;
  const std::uint32_t exp = (ax >> 23) - 127 + 15;
  std::uint32_t h = (exp << 10) | (mant >> 13);
  const std::uint32_t rest = mant & 0x1fffu;
  if (rest > 0x1000u || (rest == 0x1000u && (h & 1u))) ++h;  // a carry into the exponent is right
  return static_cast<std::uint16_t>(sign | h);
}

namespace {

std::string Base64(const std::vector<std::uint8_t>& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0,
                        b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const std::uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? k[v & 63] : '=';
  }
  return out;
}

// RGB float32 -> RGBA half, little endian (every WebGL platform's byte order), alpha 1.
std::string HalfRgbaBase64(const RgbImage& img, bool* clipped) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(8 * static_cast<std::size_t>(img.width) * img.height);
  auto put = [&](std::uint16_t h) {
    bytes.push_back(static_cast<std::uint8_t>(h & 0xff));
    bytes.push_back(static_cast<std::uint8_t>(h >> 8));
  };
  for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
    for (int c = 0; c < 3; ++c) put(ToHalf(img.rgb[i + c], clipped));
    put(0x3c00);  // 1.0
  }
  return Base64(bytes);
}

std::string Header(const Provenance& p, const char* what) {
  std::string s;
  for (const std::string& line : p.Lines()) s += "// " + CommentText(line) + "\n";
  s += std::string("//\n// A three.js ShaderMaterial of ") + what +
       ", with brdfit's own GLSL (the preview's).\n"
       "// Lit by the scene's DirectionalLights (other light types are ignored); linear radiance\n"
       "// out, converted to the renderer's output colour space; no tone mapping.\n"
       "// Use: import createMaterial from './this.mjs'; mesh.material = createMaterial();\n"
       "// (docs/exports.md, \"three.js ShaderMaterial\")\n"
       "import * as THREE from 'three';\n\n";
  return s;
}

std::string ProvenanceObject(const Provenance& p, const std::string& extra) {
  return "export const brdfit = {\n  version: " + JsString(p.version) +
         ",\n  source: " + JsString(p.source) + ",\n  material: " + JsString(p.material) +
         ",\n  model: " + JsString(p.model) + ",\n  metrics: " + JsString(p.metrics) + ",\n" +
         extra + "};\n\n";
}

std::string Shaders(const std::string& brdf_glsl) {
  return "export const vertexShader = `" + TemplateLiteral(kVertex) + "`;\n\n" +
         "export const fragmentShader = `" + TemplateLiteral(brdf_glsl) +
         TemplateLiteral(kFragmentMain) + "`;\n\n";
}

std::string CreateMaterial(const std::string& uniforms) {
  return "export default function createMaterial() {\n"
         "  return new THREE.ShaderMaterial({\n"
         "    name: 'brdfit-' + brdfit.material,\n"
         "    lights: true,\n"
         "    uniforms: THREE.UniformsUtils.merge([THREE.UniformsLib.lights, {\n" +
         uniforms +
         "    }]),\n"
         "    vertexShader,\n"
         "    fragmentShader,\n"
         "  });\n"
         "}\n";
}

}  // namespace

std::string ThreejsModule(const ThreejsAnalytic& a, const Provenance& p) {
  std::string params = "  params: [";
  for (std::size_t i = 0; i < a.params.size(); ++i) {
    params += fmt::format("{}{:.9g}", i ? ", " : "", a.params[i]);
  }
  params += "],\n";
  return Header(p, "the fitted model") + ProvenanceObject(p, params) + Shaders(a.brdf_glsl) +
         CreateMaterial("      uParams: { value: brdfit.params.slice() },\n");
}

std::string ThreejsFactoredModule(const ThreejsFactored& f, const Provenance& p,
                                  Fidelity* fidelity) {
  std::string s = Header(p, "the factorization");
  s += "// The texels are rounded to half floats (relative error <= 2^-11); the lookup is the\n"
       "// preview's (bilinear, texel centres, clamp to edge), filtered in the shader with float\n"
       "// weights (texelFetch), so the texture unit samples the nearest texel only.\n\n";
  s += ProvenanceObject(
      p, fmt::format("  parameterization: {},\n  rank: {},\n  diffuse: [{:.9g}, {:.9g}, {:.9g}],\n",
                     JsString(f.parameterization), f.p.size(), f.diffuse[0], f.diffuse[1],
                     f.diffuse[2]));
  s += "// Half-float RGBA texels, little endian, row 0 first (texture coordinate t = 0).\n"
       "function halfTexture(base64, width, height, repeatRows) {\n"
       "  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));\n"
       "  const t = new THREE.DataTexture(new Uint16Array(bytes.buffer), width, height,\n"
       "                                  THREE.RGBAFormat, THREE.HalfFloatType);\n"
       "  t.minFilter = THREE.NearestFilter;\n  t.magFilter = THREE.NearestFilter;\n"
       "  t.generateMipmaps = false;\n  t.wrapS = THREE.ClampToEdgeWrapping;\n"
       "  t.wrapT = repeatRows ? THREE.RepeatWrapping : THREE.ClampToEdgeWrapping;\n"
       "  t.colorSpace = THREE.NoColorSpace;\n  t.needsUpdate = true;\n  return t;\n}\n\n";
  bool clipped = false;
  std::string uniforms =
      fmt::format("      uFactorDiffuse: {{ value: new THREE.Vector3({:.9g}, {:.9g}, {:.9g}) }},\n",
                  f.diffuse[0], f.diffuse[1], f.diffuse[2]);
  const bool repeat_q = f.parameterization == "halfdiff";
  s += "const textures = {\n";
  for (std::size_t k = 0; k < f.p.size(); ++k) {
    const std::string n = k == 0 ? "" : std::to_string(k + 1);
    for (const bool q : {false, true}) {
      const RgbImage& img = q ? f.q[k] : f.p[k];
      const std::string name = std::string(q ? "uFactorQ" : "uFactorP") + n;
      s += fmt::format("  {}: [\"{}\", {}, {}, {}],\n", name, HalfRgbaBase64(img, &clipped),
                       img.width, img.height, q && repeat_q ? "true" : "false");
      uniforms += fmt::format("      {0}: {{ value: halfTexture(...textures.{0}) }},\n", name);
    }
  }
  s += "};\n\n";
  if (clipped) {
    fidelity->approximations.push_back(
        "texels above 65504 (the largest half float) are clipped to it");
  }
  s += Shaders(f.brdf_glsl) + CreateMaterial(uniforms);
  return s;
}

}  // namespace brdfit::exports
