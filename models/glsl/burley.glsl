// GLSL twin of models/burley.h "burley": Burley 2012 diffuse with Frostbite's renormalization
// (Lagarde & de Rousiers 2014, Listing 1), r = sqrt(alpha):
// f_d = kd / pi F(cos_i) F(cos_o) lerp(1, 1/1.51, r), F(c) = 1 + (F_D90 - 1)(1 - c)^5,
// F_D90 = 0.5 r + 2 r cos_d^2. f_r in 1/sr, without the cosine.
// brdfit-requires: models/glsl/math.glsl
vec3 brdfit_burley(const in brdfit_burley_params p, const in BrdfGeometry g) {
  float r = sqrt(p.alpha);
  float bias = 0.5 * r;
  float factor = 1.0 + (1.0 / 1.51 - 1.0) * r;
  float fd90 = bias + 2.0 * (g.cos_d * g.cos_d) * r;
  float fl = 1.0 + (fd90 - 1.0) * brdfit_Pow5(1.0 - g.cos_i);
  float fv = 1.0 + (fd90 - 1.0) * brdfit_Pow5(1.0 - g.cos_o);
  return vec3(p.kd_r, p.kd_g, p.kd_b) * (fl * fv * factor * RECIPROCAL_PI);
}
