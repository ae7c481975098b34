// GLSL twin of models/ue4.h "ue4" (Karis 2013, "Real Shading in Unreal Engine 4"):
// f_r = (1 - m) base / pi + D_GGX G_SchlickSmith F_Schlick / (4 cos_i cos_o),
// k = (sqrt(alpha) + 1)^2 / 8, F0 = mix(0.04, base, m). f_r in 1/sr, without the cosine.
// brdfit-requires: models/glsl/ndf.glsl
// brdfit-requires: models/glsl/masking.glsl
// brdfit-requires: models/glsl/fresnel.glsl
vec3 brdfit_ue4(const in brdfit_ue4_params p, const in BrdfGeometry g) {
  float m = p.metallic;
  float alpha = p.alpha;
  float G = brdfit_GSchlickSmith(brdfit_SchlickKUe4(alpha), g);
  float dg = brdfit_DGgx(alpha, g.cos_h, g.sin2_h) * G / (4.0 * g.cos_i * g.cos_o);
  vec3 base = vec3(p.base_r, p.base_g, p.base_b);
  vec3 f0 = 0.04 * (1.0 - m) + base * m;
  return (1.0 - m) * base * RECIPROCAL_PI + dg * brdfit_FSchlick(f0, g.cos_d);
}
