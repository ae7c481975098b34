// GLSL twin of models/lafortune.h "lafortune" (Lafortune et al. 1997, eq. 5-6, isotropic,
// C_z = 1): f_r = rho (n + 2) / (2 pi) max(0, cxy (u_x v_x + u_y v_y) + u_z v_z)^n.
// f_r in 1/sr, without the cosine.
// brdfit-requires: models/glsl/math.glsl
/* brdfit-params lafortune
   name  unit lower upper init scale  role
   rho_r 1    0     1e3   0.1  linear weight_r
   rho_g 1    0     1e3   0.1  linear weight_g
   rho_b 1    0     1e3   0.1  linear weight_b
   cxy   1    -1.1  1.1   -1   linear shape
   n     1    1     5000  20   log    shape
*/
vec3 brdfit_lafortune(const in float p[5], const in BrdfGeometry g) {
  float sxy = g.wi.x * g.wo.x + g.wi.y * g.wo.y;
  float base = p[3] * sxy + g.wi.z * g.wo.z;
  float lobe = (p[4] + 2.0) / (2.0 * PI) * brdfit_PowClipped(base, p[4]);
  return vec3(p[0], p[1], p[2]) * lobe;
}
