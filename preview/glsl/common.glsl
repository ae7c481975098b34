// Shared fragment-stage code: constants, Three.js r8x's structs and punctual lights (as in
// mebiusbox 2018's sample, docs/models.md), and the BRDF geometry every model twin reads (twin of
// models/geometry.h). Lighting is computed in view (camera) space, as Three.js does.
#define PI 3.14159265358979
#define RECIPROCAL_PI 0.318309886183791
#define saturate(a) clamp(a, 0.0, 1.0)

struct IncidentLight { vec3 color; vec3 direction; bool visible; };
struct GeometricContext { vec3 position; vec3 normal; vec3 viewDir; };

// Three.js r8x lights_pars (testLightInRange): distance 0 = unlimited range.
bool testLightInRange(const in float lightDistance, const in float cutoffDistance) {
  return any(bvec2(cutoffDistance == 0.0, lightDistance < cutoffDistance));
}
// Three.js r8x: pow(saturate(1 - d / cutoff), decay) when decay > 0. The scene loader rejects
// decay > 0 with distance 0 (that formula would divide by zero and return black).
float punctualLightIntensityToIrradianceFactor(const in float lightDistance,
                                               const in float cutoffDistance,
                                               const in float decayExponent) {
  if (decayExponent > 0.0) {
    return pow(saturate(-lightDistance / cutoffDistance + 1.0), decayExponent);
  }
  return 1.0;
}

struct DirectionalLight { vec3 direction; vec3 color; };  // direction: towards the light, view space
struct PointLight { vec3 position; vec3 color; float distance; float decay; };
struct SpotLight {
  vec3 position; vec3 direction; vec3 color;  // direction: from the target back to the light
  float distance; float decay; float coneCos; float penumbraCos;
};

void getDirectionalDirectLightIrradiance(const in DirectionalLight directionalLight,
                                         const in GeometricContext geometry,
                                         out IncidentLight directLight) {
  directLight.color = directionalLight.color;
  directLight.direction = directionalLight.direction;
  directLight.visible = true;
}

void getPointDirectLightIrradiance(const in PointLight pointLight,
                                   const in GeometricContext geometry,
                                   out IncidentLight directLight) {
  vec3 L = pointLight.position - geometry.position;
  directLight.direction = normalize(L);
  float lightDistance = length(L);
  if (testLightInRange(lightDistance, pointLight.distance)) {
    directLight.color = pointLight.color *
        punctualLightIntensityToIrradianceFactor(lightDistance, pointLight.distance, pointLight.decay);
    directLight.visible = true;
  } else {
    directLight.color = vec3(0.0);
    directLight.visible = false;
  }
}

void getSpotDirectLightIrradiance(const in SpotLight spotLight, const in GeometricContext geometry,
                                  out IncidentLight directLight) {
  vec3 L = spotLight.position - geometry.position;
  directLight.direction = normalize(L);
  float lightDistance = length(L);
  float angleCos = dot(directLight.direction, spotLight.direction);
  if (all(bvec2(angleCos > spotLight.coneCos, testLightInRange(lightDistance, spotLight.distance)))) {
    // smoothstep is undefined for edge0 >= edge1 (penumbra 0): a hard edge, as Three.js gets.
    float spotEffect = spotLight.penumbraCos > spotLight.coneCos
        ? smoothstep(spotLight.coneCos, spotLight.penumbraCos, angleCos) : 1.0;
    directLight.color = spotLight.color * spotEffect *
        punctualLightIntensityToIrradianceFactor(lightDistance, spotLight.distance, spotLight.decay);
    directLight.visible = true;
  } else {
    directLight.color = vec3(0.0);
    directLight.visible = false;
  }
}

// Twin of brdfit::Geometry (models/geometry.h): local frame, z = normal, directions away from
// the surface. sin2_h and the tangents come from components, so nothing cancels at the pole.
struct BrdfGeometry {
  vec3 wi; vec3 wo; vec3 h;
  float cos_i; float cos_o; float cos_h; float cos_d; float sin2_h; float cos_r;
};

BrdfGeometry MakeBrdfGeometry(vec3 wi, vec3 wo) {
  BrdfGeometry g;
  g.wi = wi;
  g.wo = wo;
  g.h = normalize(wi + wo);
  g.cos_i = wi.z;
  g.cos_o = wo.z;
  g.cos_h = g.h.z;
  g.cos_d = dot(wi, g.h);
  g.sin2_h = g.h.x * g.h.x + g.h.y * g.h.y;
  g.cos_r = 2.0 * wi.z * wo.z - dot(wi, wo);
  return g;
}

// Orthonormal tangent frame around a unit normal: Duff et al. 2017, "Building an Orthonormal
// Basis, Revisited" (JCGT 6(1)), Listing 3. Isotropic models do not depend on its azimuth.
void BuildFrame(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}
