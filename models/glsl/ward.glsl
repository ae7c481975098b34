// GLSL twin of models/ward.h "ward": isotropic Ward 1992 eq. 4,
// f_r = rho_s exp(-tan^2 th_h / alpha^2) / (4 pi alpha^2 sqrt(cos_i cos_o)). 1/sr, no cosine.
/* brdfit-params ward
   name    unit lower upper init scale  role
   rho_s_r 1    0     1e3   0.1  linear weight_r
   rho_s_g 1    0     1e3   0.1  linear weight_g
   rho_s_b 1    0     1e3   0.1  linear weight_b
   alpha   1    1e-4  1     0.1  log    shape
*/
vec3 brdfit_ward(const in float p[4], const in BrdfGeometry g) {
  float a2 = p[3] * p[3];
  float tan2_h = g.sin2_h / (g.cos_h * g.cos_h);
  float spec = exp(-tan2_h / a2) / (4.0 * PI * a2 * sqrt(g.cos_i * g.cos_o));
  return vec3(p[0], p[1], p[2]) * spec;
}
