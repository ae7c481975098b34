#include "export/threejs_module.h"

#include <fmt/core.h>

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

// A JS string literal (JSON's escaping is JS's).
std::string JsString(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20 || c >= 0x7f) {
      out += fmt::format("\\u{:04x}", c);
    } else {
      out += ch;
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

std::string ThreejsModule(const ThreejsAnalytic& a, const Provenance& p) {
  std::string s;
  for (const std::string& line : p.Lines()) s += "// " + line + "\n";
  s += "//\n// A three.js ShaderMaterial of the fitted model, with brdfit's own GLSL (the preview's).\n"
       "// Lit by the scene's DirectionalLights (other light types are ignored); linear radiance\n"
       "// out, converted to the renderer's output colour space; no tone mapping.\n"
       "// Use: import createMaterial from './this.mjs'; mesh.material = createMaterial();\n"
       "// (docs/exports.md, \"three.js ShaderMaterial\")\n";
  s += "import * as THREE from 'three';\n\n";
  s += "export const brdfit = {\n";
  s += "  version: " + JsString(p.version) + ",\n";
  s += "  source: " + JsString(p.source) + ",\n";
  s += "  material: " + JsString(p.material) + ",\n";
  s += "  model: " + JsString(a.model) + ",\n";
  s += "  metrics: " + JsString(p.metrics) + ",\n";
  s += "  params: [";
  for (std::size_t i = 0; i < a.params.size(); ++i) {
    s += fmt::format("{}{:.9g}", i ? ", " : "", a.params[i]);
  }
  s += "],\n};\n\n";
  s += "export const vertexShader = `" + TemplateLiteral(kVertex) + "`;\n\n";
  s += "export const fragmentShader = `" + TemplateLiteral(a.brdf_glsl) +
       TemplateLiteral(kFragmentMain) + "`;\n\n";
  s += "export default function createMaterial() {\n"
       "  return new THREE.ShaderMaterial({\n"
       "    name: 'brdfit-' + brdfit.material,\n"

       "    lights: true,\n"
       "    uniforms: THREE.UniformsUtils.merge([THREE.UniformsLib.lights,\n"
       "                                         { uParams: { value: brdfit.params.slice() } }]),\n"
       "    vertexShader,\n"
       "    fragmentShader,\n"
       "  });\n"
       "}\n";
  return s;
}

}  // namespace brdfit::exports
