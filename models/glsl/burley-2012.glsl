// GLSL twin of models/burley.h "burley-2012": Burley 2012 diffuse as published (Blender Cycles'
// Principled diffuse), r = sqrt(alpha):
// f_d = kd / pi F(cos_i) F(cos_o), F(c) = 1 + (F_D90 - 1)(1 - c)^5, F_D90 = 0.5 + 2 r cos_d^2.
// f_r in 1/sr, without the cosine.
// brdfit-requires: models/glsl/math.glsl
vec3 brdfit_burley_2012(const in brdfit_burley_2012_params p, const in BrdfGeometry g) {
  float r = sqrt(p.alpha);
  float fd90 = 0.5 + 2.0 * (g.cos_d * g.cos_d) * r;
  float fl = 1.0 + (fd90 - 1.0) * brdfit_Pow5(1.0 - g.cos_i);
  float fv = 1.0 + (fd90 - 1.0) * brdfit_Pow5(1.0 - g.cos_o);
  return vec3(p.kd_r, p.kd_g, p.kd_b) * (fl * fv * RECIPROCAL_PI);
}
