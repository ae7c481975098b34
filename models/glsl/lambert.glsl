// GLSL twin of models/lambert.h. Lambert 1760; normalized form f_r = rho_d / pi (the cosine
// integrates to pi over the hemisphere). f_r in 1/sr, without the cosine.
/* brdfit-params lambert
   name  unit lower upper init scale  role
   kd_r  1    0     1     0.5  linear weight_r
   kd_g  1    0     1     0.5  linear weight_g
   kd_b  1    0     1     0.5  linear weight_b
*/
vec3 brdfit_lambert(const in float p[3], const in BrdfGeometry g) {
  return vec3(p[0], p[1], p[2]) * RECIPROCAL_PI;
}
