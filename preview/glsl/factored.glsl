// Rank-1 factorization from two textures (McCool, Ang, Ahmad 2001, "Homomorphic Factorization
// of BRDFs for High-Performance Rendering", SIGGRAPH, eq. 3; maps of factor/factor_param.h):
//   FACTOR_MCCOOL:   f = p(wi) q(wh) p(wo)   p: parabolic disk map, q: sqrt-theta disk map
//   otherwise:       f = p(wh) q(theta_d, phi_d)   p: sqrt-theta disk, q: theta_d/phi_d rectangle
// Texels sit at texel centres (GL_LINEAR, clamp to edge; phi_d repeats), as the CPU evaluator
// (factor/factor_eval.h). Per light: two texture fetches; p(wo) of mccool is fetched once per
// fragment. Point and directional lights only with this material (the limit course notes give
// for factored BRDFs, docs/preview.md; spot lights are dropped by the renderer, which says so).
// brdfit-requires: preview/glsl/halfdiff.glsl
uniform sampler2D uFactorP;
uniform sampler2D uFactorQ;

// Heidrich & Seidel 1998, "View-independent Environment Maps", eq. 1: (s, t) = (x, y) / (1 + z).
vec2 brdfit_DiskParabolic(vec3 w) { return w.xy / (1.0 + w.z); }
// MERL's theta warp on the disk: rho = sqrt(theta / (pi/2)), (s, t) = rho (cos phi, sin phi).
vec2 brdfit_DiskSqrtTheta(vec3 w) {
  float r_xy = length(w.xy);
  if (r_xy == 0.0) return vec2(0.0);
  float rho = sqrt(atan(r_xy, w.z) / (0.5 * PI));
  return rho * w.xy / r_xy;
}
vec3 brdfit_Disk(sampler2D t, vec2 st) { return texture(t, 0.5 * (st + 1.0)).rgb; }

#if FACTOR_MCCOOL
vec3 gFactorPwo;
bool gFactorPwoReady = false;
vec3 EvalBrdf(const in BrdfGeometry g) {
  if (!gFactorPwoReady) {
    gFactorPwo = brdfit_Disk(uFactorP, brdfit_DiskParabolic(g.wo));
    gFactorPwoReady = true;
  }
  return brdfit_Disk(uFactorP, brdfit_DiskParabolic(g.wi)) *
         brdfit_Disk(uFactorQ, brdfit_DiskSqrtTheta(g.h)) * gFactorPwo;
}
#else
vec3 EvalBrdf(const in BrdfGeometry g) {
  vec3 a = brdfit_HalfDiff(g);
  return brdfit_Disk(uFactorP, brdfit_DiskSqrtTheta(g.h)) *
         texture(uFactorQ, vec2(a.y / (0.5 * PI), a.z / PI)).rgb;
}
#endif
