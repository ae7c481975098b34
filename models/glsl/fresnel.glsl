// Fresnel terms F(c), c = wi.h = cos_d (twin of models/microfacet/fresnel.h).
// brdfit-requires: models/glsl/math.glsl

// SchlickFresnel: Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering"
// (CGF 13(3)), eq. 15, F = F0 + (1 - F0)(1 - c)^5; per channel for a colour F0.
float brdfit_FSchlick(float f0, float c) { return f0 + (1.0 - f0) * brdfit_Pow5(1.0 - c); }
vec3 brdfit_FSchlick(vec3 f0, float c) { return f0 + (1.0 - f0) * brdfit_Pow5(1.0 - c); }
