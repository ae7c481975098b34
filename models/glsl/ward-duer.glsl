// GLSL twin of models/ward.h "ward-duer": Ward's lobe with Duer 2006's normalization,
// f_r = rho_s exp(-tan^2 th_h / alpha^2) / (4 pi alpha^2 cos_i cos_o). 1/sr, no cosine.
/* brdfit-params ward-duer
   name    unit lower upper init scale  role
   rho_s_r 1    0     1e3   0.1  linear weight_r
   rho_s_g 1    0     1e3   0.1  linear weight_g
   rho_s_b 1    0     1e3   0.1  linear weight_b
   alpha   1    1e-4  1     0.1  log    shape
*/
vec3 brdfit_ward_duer(const in float p[4], const in BrdfGeometry g) {
  float a2 = p[3] * p[3];
  float tan2_h = g.sin2_h / (g.cos_h * g.cos_h);
  float spec = exp(-tan2_h / a2) / (4.0 * PI * a2 * (g.cos_i * g.cos_o));
  return vec3(p[0], p[1], p[2]) * spec;
}
