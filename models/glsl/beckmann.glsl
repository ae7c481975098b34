// GLSL twin of models/beckmann.h "beckmann": Walter et al. 2007 eq. 20 with Beckmann D
// (eq. 25) and separable Smith G with the exact Beckmann Lambda; Fresnel folded into ks.
// f_r in 1/sr, without the cosine.
// brdfit-requires: models/glsl/microfacet.glsl
/* brdfit-params beckmann
   name  unit lower upper init scale  role
   ks_r  1    0     1e3   0.1  linear weight_r
   ks_g  1    0     1e3   0.1  linear weight_g
   ks_b  1    0     1e3   0.1  linear weight_b
   alpha 1    1e-4  1     0.1  log    shape
*/
vec3 brdfit_beckmann(const in float p[4], const in BrdfGeometry g) {
  float alpha = p[3];
  float G = 1.0 / ((1.0 + brdfit_LambdaBeckmann(alpha, g.wi)) *
                   (1.0 + brdfit_LambdaBeckmann(alpha, g.wo)));
  float spec = brdfit_DBeckmann(alpha, g.cos_h, g.sin2_h) * G / (4.0 * g.cos_i * g.cos_o);
  return vec3(p[0], p[1], p[2]) * spec;
}
