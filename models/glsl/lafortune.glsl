// GLSL twin of models/lafortune.h "lafortune" (Lafortune et al. 1997, eq. 5-6, isotropic,
// C_z = 1) with the C++ model's smooth Ngan-style bound 1/sqrt(1 + cxy^(2n)):
//   f_r = rho (n + 2) / (2 pi) max(0, cxy (u_x v_x + u_y v_y) + u_z v_z)^n / sqrt(1 + cxy^(2n)).
// Evaluated in log space as in C++: exp(n log(base) - softplus(n log(cxy^2)) / 2).
// f_r in 1/sr, without the cosine.
vec3 brdfit_lafortune(const in brdfit_lafortune_params p, const in BrdfGeometry g) {
  float sxy = g.wi.x * g.wo.x + g.wi.y * g.wo.y;
  float base = p.cxy * sxy + g.wi.z * g.wo.z;
  if (base <= 0.0) return vec3(0.0);  // the lobe is clipped to max(0, base)^n = 0
  float n = p.n;
  float log_shape = n * log(base);
  float c2 = p.cxy * p.cxy;
  if (c2 > 1e-30) {  // below, cxy^(2n) underflows and the bound factor is 1 (as in C++)
    float t = n * log(c2);
    // softplus(t) = log(1 + e^t), stable for both signs of t.
    float softplus = t > 0.0 ? t + log(1.0 + exp(-t)) : log(1.0 + exp(t));
    log_shape -= 0.5 * softplus;
  }
  float lobe = (n + 2.0) / (2.0 * PI) * exp(log_shape);
  return vec3(p.rho_r, p.rho_g, p.rho_b) * lobe;
}
