// A factorization from its textures: a diffuse value plus FACTOR_RANK (1..4) products (McCool,
// Ang, Ahmad 2001, "Homomorphic Factorization of BRDFs for High-Performance Rendering",
// SIGGRAPH, eq. 3; sums of products: Kautz & McCool 1999, "Interactive Rendering with Arbitrary
// BRDFs using Separable Approximations", EGWR; maps of factor/factor_param.h):
//   FACTOR_MCCOOL:  f = d + sum_k p_k(wi) q_k(wh) p_k(wo)    p: parabolic disk, q: sqrt-theta disk
//   otherwise:      f = d + sum_k p_k(wh) q_k(theta_d, phi_d) p: sqrt-theta disk, q: rectangle
// d = uFactorDiffuse (kd / pi, 1/sr; zero for the pure form); term k's textures are uFactorP,
// uFactorQ (k = 1), uFactorP2, uFactorQ2, ... Texels sit at texel centres (bilinear, clamp to
// edge; phi_d repeats), as the CPU evaluator (factor/factor_eval.h); filtered in the shader with
// float weights (texel_filter.glsl), not by the texture unit. Per light: two texture
// fetches per term; p_k(wo) of mccool is fetched once per fragment (core/factor_form.h). Point
// and directional lights only with this material (the limit course notes give for factored
// BRDFs, docs/preview.md; spot lights are dropped by the renderer, which says so).
// brdfit-requires: preview/glsl/halfdiff.glsl
// brdfit-requires: preview/glsl/texel_filter.glsl
uniform vec3 uFactorDiffuse;
uniform sampler2D uFactorP;
uniform sampler2D uFactorQ;
#if FACTOR_RANK >= 2
uniform sampler2D uFactorP2;
uniform sampler2D uFactorQ2;
#endif
#if FACTOR_RANK >= 3
uniform sampler2D uFactorP3;
uniform sampler2D uFactorQ3;
#endif
#if FACTOR_RANK >= 4
uniform sampler2D uFactorP4;
uniform sampler2D uFactorQ4;
#endif

// Heidrich & Seidel 1998, "View-independent Environment Maps", eq. 1: (s, t) = (x, y) / (1 + z).
vec2 brdfit_DiskParabolic(vec3 w) { return w.xy / (1.0 + w.z); }
// MERL's theta warp on the disk: rho = sqrt(theta / (pi/2)), (s, t) = rho (cos phi, sin phi).
vec2 brdfit_DiskSqrtTheta(vec3 w) {
  float r_xy = length(w.xy);
  if (r_xy == 0.0) return vec2(0.0);
  float rho = sqrt(atan(r_xy, w.z) / (0.5 * PI));
  return rho * w.xy / r_xy;
}
vec3 brdfit_Disk(sampler2D t, vec2 st) { return brdfit_Bilinear(t, 0.5 * (st + 1.0), false).rgb; }

#if FACTOR_MCCOOL
// p_k(wo), once per fragment (wo does not change between lights).
vec3 gFactorPwo[FACTOR_RANK];
bool gFactorPwoReady = false;
vec3 brdfit_FactorTerm(sampler2D p, sampler2D q, vec3 p_wo, const in BrdfGeometry g) {
  return brdfit_Disk(p, brdfit_DiskParabolic(g.wi)) * brdfit_Disk(q, brdfit_DiskSqrtTheta(g.h)) *
         p_wo;
}
vec3 EvalBrdf(const in BrdfGeometry g) {
  if (!gFactorPwoReady) {
    vec2 st = brdfit_DiskParabolic(g.wo);
    gFactorPwo[0] = brdfit_Disk(uFactorP, st);
#if FACTOR_RANK >= 2
    gFactorPwo[1] = brdfit_Disk(uFactorP2, st);
#endif
#if FACTOR_RANK >= 3
    gFactorPwo[2] = brdfit_Disk(uFactorP3, st);
#endif
#if FACTOR_RANK >= 4
    gFactorPwo[3] = brdfit_Disk(uFactorP4, st);
#endif
    gFactorPwoReady = true;
  }
  vec3 f = uFactorDiffuse + brdfit_FactorTerm(uFactorP, uFactorQ, gFactorPwo[0], g);
#if FACTOR_RANK >= 2
  f += brdfit_FactorTerm(uFactorP2, uFactorQ2, gFactorPwo[1], g);
#endif
#if FACTOR_RANK >= 3
  f += brdfit_FactorTerm(uFactorP3, uFactorQ3, gFactorPwo[2], g);
#endif
#if FACTOR_RANK >= 4
  f += brdfit_FactorTerm(uFactorP4, uFactorQ4, gFactorPwo[3], g);
#endif
  return f;
}
#else
vec3 brdfit_FactorTerm(sampler2D p, sampler2D q, vec2 h_st, vec2 d_uv) {
  return brdfit_Disk(p, h_st) * brdfit_Bilinear(q, d_uv, true).rgb;  // phi_d (rows) repeats
}
vec3 EvalBrdf(const in BrdfGeometry g) {
  vec3 a = brdfit_HalfDiff(g);
  vec2 h_st = brdfit_DiskSqrtTheta(g.h);
  vec2 d_uv = vec2(a.y / (0.5 * PI), a.z / PI);
  vec3 f = uFactorDiffuse + brdfit_FactorTerm(uFactorP, uFactorQ, h_st, d_uv);
#if FACTOR_RANK >= 2
  f += brdfit_FactorTerm(uFactorP2, uFactorQ2, h_st, d_uv);
#endif
#if FACTOR_RANK >= 3
  f += brdfit_FactorTerm(uFactorP3, uFactorQ3, h_st, d_uv);
#endif
#if FACTOR_RANK >= 4
  f += brdfit_FactorTerm(uFactorP4, uFactorQ4, h_st, d_uv);
#endif
  return f;
}
#endif
