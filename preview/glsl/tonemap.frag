// Display transform: exposure and tone mapping (Three.js r8x's set: Linear, Reinhard,
// Uncharted2, OptimizedCineon), then the output encoding (exact sRGB, gamma 2.0 = Three.js's
// default GAMMA_FACTOR, or none). Twin of preview/tonemap.h. TONE_MAPPING and ENCODING are #defined
// by the renderer: 0 linear, 1 reinhard, 2 uncharted2, 3 cineon; 0 linear, 1 srgb, 2 gamma2.
uniform sampler2D uLinear;
uniform float toneMappingExposure;
uniform float toneMappingWhitePoint;
uniform vec3 uBackground;  // linear radiance where nothing was drawn
out vec4 fragColor;

#define saturate(a) clamp(a, 0.0, 1.0)
vec3 LinearToneMapping(vec3 color) { return toneMappingExposure * color; }
vec3 ReinhardToneMapping(vec3 color) {
  color *= toneMappingExposure;
  return saturate(color / (vec3(1.0) + color));
}
#define Uncharted2Helper(x) max(((x * (0.15 * x + 0.10 * 0.50) + 0.20 * 0.02) / (x * (0.15 * x + 0.50) + 0.20 * 0.30)) - 0.02 / 0.30, vec3(0.0))
vec3 Uncharted2ToneMapping(vec3 color) {
  color *= toneMappingExposure;
  return saturate(Uncharted2Helper(color) / Uncharted2Helper(vec3(toneMappingWhitePoint)));
}
vec3 OptimizedCineonToneMapping(vec3 color) {
  color *= toneMappingExposure;
  color = max(vec3(0.0), color - 0.004);
  return pow((color * (6.2 * color + 0.5)) / (color * (6.2 * color + 1.7) + 0.06), vec3(2.2));
}
// IEC 61966-2-1 sRGB encoding (exact exponent 1/2.4; Three.js's LinearTosRGB writes 0.41666).
vec3 LinearTosRGB(vec3 v) {
  return mix(pow(v, vec3(1.0 / 2.4)) * 1.055 - vec3(0.055), v * 12.92,
             vec3(lessThanEqual(v, vec3(0.0031308))));
}

void main() {
  vec4 texel = texelFetch(uLinear, ivec2(gl_FragCoord.xy), 0);
  vec3 color = texel.a > 0.0 ? texel.rgb : uBackground;
#if TONE_MAPPING == 0
  color = LinearToneMapping(color);
#elif TONE_MAPPING == 1
  color = ReinhardToneMapping(color);
#elif TONE_MAPPING == 2
  color = Uncharted2ToneMapping(color);
#else
  color = OptimizedCineonToneMapping(color);
#endif
  color = saturate(color);
#if ENCODING == 1
  color = LinearTosRGB(color);
#elif ENCODING == 2
  color = pow(color, vec3(1.0 / 2.0));
#endif
  fragColor = vec4(color, 1.0);
}
