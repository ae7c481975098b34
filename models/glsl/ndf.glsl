// Microfacet normal distributions D(h) and their Smith Lambda (twin of
// models/microfacet/ndf.h). sin^2 of a polar angle comes from components, as in C++.
// brdfit-requires: models/glsl/math.glsl

// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
// Surfaces" (EGSR), eq. 33: D = alpha^2 / (pi (alpha^2 cos^2 th + sin^2 th)^2), sin^2 from
// components (no cancellation at th -> 0).
float brdfit_DGgx(float alpha, float cos_h, float sin2_h) {
  float a2 = alpha * alpha;
  float denom = a2 * (cos_h * cos_h) + sin2_h;
  return a2 / (PI * denom * denom);
}

// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs" (JCGT
// 3(2)), §5.3: Lambda_GGX = (-1 + sqrt(1 + x)) / 2 = x / (2 (1 + sqrt(1 + x))), x = alpha^2 tan^2.
float brdfit_LambdaGgx(float alpha, vec3 v) {
  float x = alpha * alpha * ((v.x * v.x + v.y * v.y) / (v.z * v.z));
  return x / (2.0 * (1.0 + sqrt(1.0 + x)));
}

// Walter et al. 2007, eq. 25: D = exp(-tan^2 th / alpha^2) / (pi alpha^2 cos^4 th).
float brdfit_DBeckmann(float alpha, float cos_h, float sin2_h) {
  float c2 = cos_h * cos_h;
  float a2 = alpha * alpha;
  return exp(-sin2_h / (c2 * a2)) / (PI * a2 * (c2 * c2));
}

// Walter et al. 2007, §5.1; Heitz 2014, §5.3, a = 1 / (alpha tan th):
// Lambda = (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2; 0 for a > 8 (< 1e-30).
float brdfit_LambdaBeckmann(float alpha, vec3 v) {
  float inv_a = alpha * sqrt((v.x * v.x + v.y * v.y) / (v.z * v.z));
  if (inv_a < 1.0 / 8.0) return 0.0;
  float a = 1.0 / inv_a;
  return 0.5 * (exp(-a * a) * inv_a / sqrt(PI) - brdfit_Erfc(a));
}
