// GLSL twin of models/ue4.h "ue4" (Karis 2013, "Real Shading in Unreal Engine 4"):
// f_r = (1 - m) base / pi + D_GGX G_SchlickSmith F_Schlick / (4 cos_i cos_o),
// k = (sqrt(alpha) + 1)^2 / 8, F0 = mix(0.04, base, m). f_r in 1/sr, without the cosine.
// brdfit-requires: models/glsl/microfacet.glsl
/* brdfit-params ue4
   name     unit lower upper init scale  role
   base_r   1    0     1     0.5  linear shape
   base_g   1    0     1     0.5  linear shape
   base_b   1    0     1     0.5  linear shape
   metallic 1    0     1     0    linear shape
   alpha    1    1e-4  1     0.25 log    shape
*/
vec3 brdfit_ue4(const in float p[5], const in BrdfGeometry g) {
  float m = p[3];
  float alpha = p[4];
  float r1 = sqrt(alpha) + 1.0;
  float k = 0.125 * r1 * r1;  // Karis 2013 eq. 4-5
  float G = (g.cos_i / (g.cos_i * (1.0 - k) + k)) * (g.cos_o / (g.cos_o * (1.0 - k) + k));
  float dg = brdfit_DGgx(alpha, g.cos_h, g.sin2_h) * G / (4.0 * g.cos_i * g.cos_o);
  vec3 base = vec3(p[0], p[1], p[2]);
  vec3 f0 = 0.04 * (1.0 - m) + base * m;
  vec3 F = f0 + (1.0 - f0) * brdfit_Pow5(1.0 - g.cos_d);
  return (1.0 - m) * base * RECIPROCAL_PI + dg * F;
}
