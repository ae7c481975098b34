// GLSL twin of models/lambert.h. Lambert 1760; normalized form f_r = rho_d / pi (the cosine
// integrates to pi over the hemisphere). f_r in 1/sr, without the cosine.
vec3 brdfit_lambert(const in brdfit_lambert_params p, const in BrdfGeometry g) {
  return vec3(p.kd_r, p.kd_g, p.kd_b) * RECIPROCAL_PI;
}
