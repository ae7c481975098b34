// GLSL twin of models/ward.h "ward-duer": Ward's lobe with Duer 2006's normalization,
// f_r = rho_s exp(-tan^2 th_h / alpha^2) / (4 pi alpha^2 cos_i cos_o). 1/sr, no cosine.
vec3 brdfit_ward_duer(const in brdfit_ward_duer_params p, const in BrdfGeometry g) {
  float a2 = p.alpha * p.alpha;
  float tan2_h = g.sin2_h / (g.cos_h * g.cos_h);
  float spec = exp(-tan2_h / a2) / (4.0 * PI * a2 * (g.cos_i * g.cos_o));
  return vec3(p.rho_s_r, p.rho_s_g, p.rho_s_b) * spec;
}
