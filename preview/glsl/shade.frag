// Surface shading: Three.js r8x's structure (geometry, incident light, RE_Direct), per fragment in
// view space. The generator prepends #version, the #defines (light counts, object kind,
// material kind), common.glsl, the model twins the scene uses and EvalBrdf().
#if !OBJECT_SPHERE
in vec3 vViewPosition;  // surface -> camera, view space (Three.js: -mvPosition.xyz)
in vec3 vNormal;
#endif

uniform vec2 uViewport;        // framebuffer size in pixels
uniform vec2 uTanHalfFov;      // tan(fov_y / 2) * aspect, tan(fov_y / 2)
uniform mat4 uProjection;
uniform vec3 uSphereCentre;    // view space
uniform float uSphereRadius;

#if NUM_DIR_LIGHTS > 0
uniform DirectionalLight directionalLights[NUM_DIR_LIGHTS];
#endif
#if NUM_POINT_LIGHTS > 0
uniform PointLight pointLights[NUM_POINT_LIGHTS];
#endif
#if NUM_SPOT_LIGHTS > 0
uniform SpotLight spotLights[NUM_SPOT_LIGHTS];
#endif

out vec4 fragColor;

vec3 gT, gB, gN;  // tangent frame of the current fragment
vec3 ToLocal(vec3 v) { return vec3(dot(v, gT), dot(v, gB), dot(v, gN)); }

// Cosine, irradiance and BRDF for one light (Three.js RE_Direct). With PUNCTUAL_PI the light
// colour is multiplied by pi, so a white Lambert surface facing a unit light shows the light
// colour (Three.js r8x without PHYSICALLY_CORRECT_LIGHTS; docs/scenes.md).
void RE_Direct(const in IncidentLight directLight, const in vec3 wo, inout vec3 radiance) {
  vec3 wi = ToLocal(directLight.direction);
  if (wi.z <= 0.0) return;  // light below the horizon: no contribution, BRDF not evaluated
  vec3 irradiance = wi.z * directLight.color;
#if PUNCTUAL_PI
  irradiance *= PI;
#endif
  radiance += irradiance * EvalBrdf(MakeBrdfGeometry(wi, wo));
}

void main() {
  GeometricContext geometry;
#if OBJECT_SPHERE
  // Exact sphere per pixel: the ray through the pixel centre meets the sphere (the rasterized
  // proxy only decides which fragments run). Stable quadratic: Haines et al. 2019, "Precision
  // Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7), eq. 7.5 and 7.7.
  vec2 ndc = 2.0 * gl_FragCoord.xy / uViewport - 1.0;
  vec3 d = normalize(vec3(ndc * uTanHalfFov, -1.0));
  float b = dot(d, uSphereCentre);
  vec3 q = uSphereCentre - b * d;
  float disc = uSphereRadius * uSphereRadius - dot(q, q);
  if (disc < 0.0 || b <= 0.0) discard;
  float c = dot(uSphereCentre, uSphereCentre) - uSphereRadius * uSphereRadius;
  float t = c / (b + sqrt(disc));
  geometry.position = t * d;
  geometry.normal = (geometry.position - uSphereCentre) / uSphereRadius;
  geometry.viewDir = -d;
  vec4 clip = uProjection * vec4(geometry.position, 1.0);
  gl_FragDepth = 0.5 * (clip.z / clip.w) + 0.5;
#else
  geometry.position = -vViewPosition;
  geometry.normal = normalize(vNormal);
  geometry.viewDir = normalize(vViewPosition);
#endif
  gN = geometry.normal;
  BuildFrame(gN, gT, gB);
  vec3 wo = ToLocal(geometry.viewDir);
  vec3 radiance = vec3(0.0);
  if (wo.z > 0.0) {
    IncidentLight directLight;
#if NUM_POINT_LIGHTS > 0
    for (int i = 0; i < NUM_POINT_LIGHTS; ++i) {
      getPointDirectLightIrradiance(pointLights[i], geometry, directLight);
      if (directLight.visible) RE_Direct(directLight, wo, radiance);
    }
#endif
#if NUM_SPOT_LIGHTS > 0
    for (int i = 0; i < NUM_SPOT_LIGHTS; ++i) {
      getSpotDirectLightIrradiance(spotLights[i], geometry, directLight);
      if (directLight.visible) RE_Direct(directLight, wo, radiance);
    }
#endif
#if NUM_DIR_LIGHTS > 0
    for (int i = 0; i < NUM_DIR_LIGHTS; ++i) {
      getDirectionalDirectLightIrradiance(directionalLights[i], geometry, directLight);
      RE_Direct(directLight, wo, radiance);
    }
#endif
  }
  fragColor = vec4(radiance, 1.0);
}
