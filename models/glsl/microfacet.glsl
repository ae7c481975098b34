// The microfacet lobe's shape (twin of Microfacet::Shape, models/microfacet/microfacet.h):
//   D G F / (scale cos_i cos_o),  scale 4 (Walter et al. 2007 eq. 20) or pi (Cook & Torrance
//   1982 as Ngan et al. 2005 fit it).
// Each microfacet lobe's entry point is generated from its C++ type (preview/glsl_microfacet.h):
// it calls the D, G and F of models/glsl/ndf.glsl, masking.glsl and fresnel.glsl named there.
// brdfit-requires: models/glsl/ndf.glsl
// brdfit-requires: models/glsl/masking.glsl
// brdfit-requires: models/glsl/fresnel.glsl

float brdfit_MicrofacetShape(float D, float G, float F, float scale, const in BrdfGeometry g) {
  return D * G * F / (scale * g.cos_i * g.cos_o);
}
