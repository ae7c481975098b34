// GLSL twin of models/abc.h "abc" (Löw et al. 2012, smooth surface model, ABC spectrum):
// f_r = A / (1 + B |D_p|^2)^C F_Schlick(f0, wi.h), D_p = (wi + wo).xy. 1/sr, no cosine.
// brdfit-requires: models/glsl/fresnel.glsl
vec3 brdfit_abc(const in brdfit_abc_params p, const in BrdfGeometry g) {
  vec2 dp = g.wi.xy + g.wo.xy;
  float s = exp(-p.c * log(1.0 + p.b * dot(dp, dp)));
  return vec3(p.a_r, p.a_g, p.a_b) * s * brdfit_FSchlick(p.f0, g.cos_d);
}
