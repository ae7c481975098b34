// Shadowing-masking terms G(wi, wo) (twin of models/microfacet/masking.h), one function per
// C++ policy type. GLSL has no templates: the Smith terms take the NDF's Lambda(wi) and
// Lambda(wo), which the caller computes with that NDF's brdfit_Lambda* (models/glsl/ndf.glsl).

// SmithSeparable: Heitz 2014 eq. 98, G2 = 1 / ((1 + Lambda(wi)) (1 + Lambda(wo))).
float brdfit_GSmithSeparable(float lambda_i, float lambda_o) {
  return 1.0 / ((1.0 + lambda_i) * (1.0 + lambda_o));
}

// SmithHeightCorrelated: Heitz 2014 eq. 99, G2 = 1 / (1 + Lambda(wi) + Lambda(wo)).
float brdfit_GSmithHeightCorrelated(float lambda_i, float lambda_o) {
  return 1.0 / (1.0 + lambda_i + lambda_o);
}

// SchlickSmith: Schlick 1994's G1(c) = c / (c (1 - k) + k), G2 = G1(cos_i) G1(cos_o).
float brdfit_GSchlickSmith(float k, const in BrdfGeometry g) {
  return (g.cos_i / (g.cos_i * (1.0 - k) + k)) * (g.cos_o / (g.cos_o * (1.0 - k) + k));
}

// SchlickK::kUe4: Karis 2013 eq. 4-5, k = (r + 1)^2 / 8 with r = sqrt(alpha).
float brdfit_SchlickKUe4(float alpha) {
  float r1 = sqrt(alpha) + 1.0;
  return 0.125 * r1 * r1;
}

// VGroove: Cook & Torrance 1982, G = min(1, 2 (n.h)(n.wo)/(wo.h), 2 (n.h)(n.wi)/(wo.h)).
float brdfit_GVGroove(const in BrdfGeometry g) {
  float s = 2.0 * g.cos_h / g.cos_d;
  return min(1.0, min(s * g.cos_o, s * g.cos_i));
}
