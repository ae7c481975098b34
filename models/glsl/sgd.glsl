// GLSL twin of models/sgd.h "sgd" (Bagher et al. 2012 shifted gamma distribution):
// f_r = ks D_SGD G_VGroove F_Schlick / (4 cos_i cos_o),
// D_SGD = exp(-1 - y - p log(1 + y)) / (alpha Gamma(1 - p, 1) pi cos^4 th_h), y = tan^2 / alpha.
// brdfit-requires: models/glsl/masking.glsl
// brdfit-requires: models/glsl/fresnel.glsl

// Gamma(s, 1) for s in [-1, 1]: the Taylor polynomial of models/sgd.h UpperGammaAt1.
float brdfit_UpperGammaAt1(float s) {
  float c[20] = float[20](2.193839344e-01, 9.784319722e-02, 3.560349193e-02, 1.107089545e-02, 3.027611196e-03, 7.426583005e-04, 1.657562561e-04, 3.403139487e-05, 6.482609817e-06, 1.153713529e-06, 1.929374388e-07, 3.046491368e-08, 4.560725360e-09, 6.496199486e-10, 8.831206054e-11, 1.148942821e-11, 1.433981078e-12, 1.720647559e-13, 1.988776648e-14, 2.218129017e-15);
  float acc = c[19];
  for (int k = 18; k >= 0; --k) acc = acc * s + c[k];
  return acc;
}

vec3 brdfit_sgd(const in brdfit_sgd_params p, const in BrdfGeometry g) {
  float c2 = g.cos_h * g.cos_h;
  float y = (g.sin2_h / c2) / p.alpha;
  float D = exp(-1.0 - y - p.p * log(1.0 + y)) /
            (p.alpha * brdfit_UpperGammaAt1(1.0 - p.p) * PI * (c2 * c2));
  float spec = D * brdfit_GVGroove(g) * brdfit_FSchlick(p.f0, g.cos_d) / (4.0 * g.cos_i * g.cos_o);
  return vec3(p.ks_r, p.ks_g, p.ks_b) * spec;
}
