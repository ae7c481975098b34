// GLSL twin of models/blinn_phong.h "blinn-phong": f_r = ks (n + 8) / (8 pi) cos^n th_h
// (Blinn 1977; Real-Time Rendering 3rd ed. eq. 7.49). f_r in 1/sr, without the cosine.
// brdfit-requires: models/glsl/math.glsl
/* brdfit-params blinn-phong
   name unit lower upper init scale  role
   ks_r 1    0     1e3   0.1  linear weight_r
   ks_g 1    0     1e3   0.1  linear weight_g
   ks_b 1    0     1e3   0.1  linear weight_b
   n    1    1     1e5   100  log    shape
*/
vec3 brdfit_blinn_phong(const in float p[4], const in BrdfGeometry g) {
  float n = p[3];
  float spec = (n + 8.0) / (8.0 * PI) * brdfit_PowCosFromSin2(g.sin2_h, n);
  return vec3(p[0], p[1], p[2]) * spec;
}
