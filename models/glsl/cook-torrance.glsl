// GLSL twin of models/cook_torrance.h "cook-torrance" (Cook & Torrance 1982 as Ngan et al.
// 2005 fit it): f_r = ks F_Schlick(F0, wi.h) D_Beckmann G_Vgroove / (pi cos_i cos_o),
// G = min(1, 2 (n.h)(n.wo)/(wo.h), 2 (n.h)(n.wi)/(wo.h)). f_r in 1/sr, without the cosine.
// brdfit-requires: models/glsl/microfacet.glsl
/* brdfit-params cook-torrance
   name  unit lower upper init scale  role
   ks_r  1    0     1e3   0.1  linear weight_r
   ks_g  1    0     1e3   0.1  linear weight_g
   ks_b  1    0     1e3   0.1  linear weight_b
   alpha 1    1e-4  1     0.1  log    shape
   f0    1    0     1     0.04 linear shape
*/
vec3 brdfit_cook_torrance(const in float p[5], const in BrdfGeometry g) {
  float alpha = p[3];
  float s = 2.0 * g.cos_h / g.cos_d;
  float G = min(1.0, min(s * g.cos_o, s * g.cos_i));
  float spec = brdfit_DBeckmann(alpha, g.cos_h, g.sin2_h) * G * brdfit_FSchlick(p[4], g.cos_d) /
               (PI * g.cos_i * g.cos_o);
  return vec3(p[0], p[1], p[2]) * spec;
}
