// GLSL twin of models/phong.h "phong": normalized Phong (Lewis 1994),
// f_r = ks (n + 2) / (2 pi) max(0, cos alpha_r)^n. 1 - cos alpha_r = |wo - reflect(wi)|^2 / 2
// avoids cancellation near the mirror direction. f_r in 1/sr, without the cosine.
// brdfit-requires: models/glsl/math.glsl
vec3 brdfit_phong(const in brdfit_phong_params p, const in BrdfGeometry g) {
  if (g.cos_r <= 0.0) return vec3(0.0);
  float n = p.n;
  vec3 d = vec3(g.wo.x + g.wi.x, g.wo.y + g.wi.y, g.wo.z - g.wi.z);
  float spec = (n + 2.0) / (2.0 * PI) * exp(n * brdfit_Log1p(-0.5 * dot(d, d)));
  return vec3(p.ks_r, p.ks_g, p.ks_b) * spec;
}
