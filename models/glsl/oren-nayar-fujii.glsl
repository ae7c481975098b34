// GLSL twin of models/oren_nayar.h "oren-nayar-fujii" (Fujii 2012, improved Oren-Nayar; Blender
// Cycles' Diffuse BSDF): f_r = kd A (1 + sigma s / t), A = 1 / (pi + (pi/2 - 2/3) sigma),
// s = wi.x wo.x + wi.y wo.y, t = max(cos_i, cos_o) if s > 0 else 1. f_r in 1/sr, no cosine.
vec3 brdfit_oren_nayar_fujii(const in brdfit_oren_nayar_fujii_params p, const in BrdfGeometry g) {
  float a = 1.0 / (PI + (0.5 * PI - 2.0 / 3.0) * p.sigma);
  float s = g.wi.x * g.wo.x + g.wi.y * g.wo.y;
  float st = s > 0.0 ? s / max(g.cos_i, g.cos_o) : s;
  return vec3(p.kd_r, p.kd_g, p.kd_b) * (a * (1.0 + p.sigma * st));
}
