// GLSL twin of models/blinn_phong.h "blinn-phong": f_r = ks (n + 8) / (8 pi) cos^n th_h
// (Blinn 1977; Real-Time Rendering 3rd ed. eq. 7.49). f_r in 1/sr, without the cosine.
// brdfit-requires: models/glsl/math.glsl
vec3 brdfit_blinn_phong(const in brdfit_blinn_phong_params p, const in BrdfGeometry g) {
  float n = p.n;
  float spec = (n + 8.0) / (8.0 * PI) * brdfit_PowCosFromSin2(g.sin2_h, n);
  return vec3(p.ks_r, p.ks_g, p.ks_b) * spec;
}
