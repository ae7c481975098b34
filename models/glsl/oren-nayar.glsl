// GLSL twin of models/oren_nayar.h "oren-nayar" (Oren & Nayar 1994, eq. 30, vector form):
// f_r = kd / pi (A + B max(0, wi.x wo.x + wi.y wo.y) / max(cos_i, cos_o)),
// A = 1 - 0.5 s^2 / (s^2 + 0.33), B = 0.45 s^2 / (s^2 + 0.09). f_r in 1/sr, no cosine.
/* brdfit-params oren-nayar
   name  unit lower upper   init scale  role
   kd_r  1    0     1       0.5  linear weight_r
   kd_g  1    0     1       0.5  linear weight_g
   kd_b  1    0     1       0.5  linear weight_b
   sigma rad  0     1.5707963267948966 0.3 linear shape
*/
vec3 brdfit_oren_nayar(const in float p[4], const in BrdfGeometry g) {
  float s2 = p[3] * p[3];
  float a = 1.0 - 0.5 * s2 / (s2 + 0.33);
  float b = 0.45 * s2 / (s2 + 0.09);
  float sxy = g.wi.x * g.wo.x + g.wi.y * g.wo.y;
  float geo = max(0.0, sxy) / max(g.cos_i, g.cos_o);
  return vec3(p[0], p[1], p[2]) * ((a + b * geo) * RECIPROCAL_PI);
}
