// GLSL twin of models/sheen.h "sheen" (Estevez & Kulla 2017 Charlie D, Neubelt & Pettineo 2013 V):
// f_r = sheen (2 + 1/alpha) sin(th_h)^(1/alpha) / (2 pi) / (4 (cos_i + cos_o - cos_i cos_o)).
vec3 brdfit_sheen(const in brdfit_sheen_params p, const in BrdfGeometry g) {
  float d = g.sin2_h > 0.0
      ? (2.0 + 1.0 / p.alpha) * exp(0.5 * log(g.sin2_h) / p.alpha) * (0.5 * RECIPROCAL_PI)
      : 0.0;
  float v = 1.0 / (4.0 * (g.cos_i + g.cos_o - g.cos_i * g.cos_o));
  return vec3(p.sheen_r, p.sheen_g, p.sheen_b) * (d * v);
}
