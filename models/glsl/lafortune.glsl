// GLSL twin of models/lafortune.h "lafortune" (Lafortune et al. 1997, eq. 5-6, isotropic,
// C_z = 1) with the C++ model's smooth Ngan-style bound 1/sqrt(1 + cxy^(2n)):
//   f_r = rho (n + 2) / (2 pi) max(0, cxy (u_x v_x + u_y v_y) + u_z v_z)^n / sqrt(1 + cxy^(2n)).
// Evaluated in log space as in C++: exp(n log(base) - softplus(n log(cxy^2)) / 2).
// f_r in 1/sr, without the cosine.
// brdfit-requires: models/glsl/math.glsl
/* brdfit-params lafortune
   name  unit lower upper init scale  role
   rho_r 1    0     1e3   0.1  linear weight_r
   rho_g 1    0     1e3   0.1  linear weight_g
   rho_b 1    0     1e3   0.1  linear weight_b
   cxy   1    -25   25    -1   linear shape
   n     1    1     1e5   20   log    shape
*/
vec3 brdfit_lafortune(const in float p[5], const in BrdfGeometry g) {
  float sxy = g.wi.x * g.wo.x + g.wi.y * g.wo.y;
  float base = p[3] * sxy + g.wi.z * g.wo.z;
  if (base <= 0.0) return vec3(0.0);  // the lobe is clipped to max(0, base)^n = 0
  float n = p[4];
  float log_shape = n * log(base);
  float c2 = p[3] * p[3];
  if (c2 > 1e-30) {  // below, cxy^(2n) underflows and the bound factor is 1 (as in C++)
    float t = n * log(c2);
    // softplus(t) = log(1 + e^t), stable for both signs of t.
    float softplus = t > 0.0 ? t + log(1.0 + exp(-t)) : log(1.0 + exp(t));
    log_shape -= 0.5 * softplus;
  }
  float lobe = (n + 2.0) / (2.0 * PI) * exp(log_shape);
  return vec3(p[0], p[1], p[2]) * lobe;
}
