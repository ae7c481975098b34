// GLSL twin of models/ggx.h "ggx-f0": GGX D (Walter et al. 2007 eq. 33), height-correlated
// Smith G2 (Heitz 2014 eq. 99) and Schlick F (Schlick 1994 eq. 15) with an RGB F0, no weight:
// f_r = D G2 F / (4 cos_i cos_o). Built from the terms' twins (ndf, masking, fresnel .glsl);
// hand-written because the per-channel F is not the scalar F of brdfit_MicrofacetShape.
// brdfit-requires: models/glsl/ndf.glsl
// brdfit-requires: models/glsl/masking.glsl
// brdfit-requires: models/glsl/fresnel.glsl
vec3 brdfit_ggx_f0(const in brdfit_ggx_f0_params p, const in BrdfGeometry g) {
  float alpha = p.alpha;
  float G = brdfit_GSmithHeightCorrelated(brdfit_LambdaGgx(alpha, g.wi),
                                          brdfit_LambdaGgx(alpha, g.wo));
  float dg = brdfit_DGgx(alpha, g.cos_h, g.sin2_h) * G / (4.0 * g.cos_i * g.cos_o);
  return dg * brdfit_FSchlick(vec3(p.f0_r, p.f0_g, p.f0_b), g.cos_d);
}
