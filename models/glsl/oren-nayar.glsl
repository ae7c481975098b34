// GLSL twin of models/oren_nayar.h "oren-nayar" (Oren & Nayar 1994, eq. 30, vector form):
// f_r = kd / pi (A + B max(0, wi.x wo.x + wi.y wo.y) / max(cos_i, cos_o)),
// A = 1 - 0.5 s^2 / (s^2 + 0.33), B = 0.45 s^2 / (s^2 + 0.09). f_r in 1/sr, no cosine.
vec3 brdfit_oren_nayar(const in brdfit_oren_nayar_params p, const in BrdfGeometry g) {
  float s2 = p.sigma * p.sigma;
  float a = 1.0 - 0.5 * s2 / (s2 + 0.33);
  float b = 0.45 * s2 / (s2 + 0.09);
  float sxy = g.wi.x * g.wo.x + g.wi.y * g.wo.y;
  float geo = max(0.0, sxy) / max(g.cos_i, g.cos_o);
  return vec3(p.kd_r, p.kd_g, p.kd_b) * ((a + b * geo) * RECIPROCAL_PI);
}
