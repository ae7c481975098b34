// Independent oracles: every model written again in its paper's own form, from polar angles
// (theta_i, phi_i, theta_o, phi_o) and the half/difference angles derived from them with
// atan2 — not the vector forms of models/. Parameter vectors use the models' order
// (`brdfit models`). f_r in 1/sr, without the cosine.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>

namespace brdfit::oracle {

constexpr double kPi = 3.14159265358979323846;

struct Angles {
  double ti, pi, to, po;  // polar and azimuthal angles of wi and wo (radians)
};

struct V3 {
  double x, y, z;
};
inline V3 Dir(double t, double p) {
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}
inline double Dot(const V3& a, const V3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// Half-vector polar angle theta_h and azimuth phi_h, and the difference angle theta_d
// (angle between wi and h), all through atan2 so that they are accurate near 0.
struct HalfAngles {
  double th, ph, td;
};
inline HalfAngles Half(const Angles& a) {
  const V3 i = Dir(a.ti, a.pi), o = Dir(a.to, a.po);
  V3 h = {i.x + o.x, i.y + o.y, i.z + o.z};
  const double len = std::sqrt(Dot(h, h));
  h = {h.x / len, h.y / len, h.z / len};
  const V3 c = {i.y * h.z - i.z * h.y, i.z * h.x - i.x * h.z, i.x * h.y - i.y * h.x};
  return {std::atan2(std::hypot(h.x, h.y), h.z), std::atan2(h.y, h.x),
          std::atan2(std::sqrt(Dot(c, c)), Dot(i, h))};
}

// ---- terms -----------------------------------------------------------------------------------

// Walter et al. 2007 eq. 33.
inline double DGgx(double alpha, double th) {
  const double c = std::cos(th), t = std::tan(th), a2 = alpha * alpha;
  return a2 / (kPi * std::pow(c, 4) * (a2 + t * t) * (a2 + t * t));
}
// Walter et al. 2007 eq. 34.
inline double G1Ggx(double alpha, double theta) {
  const double t = std::tan(theta);
  return 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * t * t));
}
// Heitz 2014 §5.3, GGX Lambda, direct form.
inline double LambdaGgx(double alpha, double theta) {
  const double t = std::tan(theta);
  return 0.5 * (-1.0 + std::sqrt(1.0 + alpha * alpha * t * t));
}
// Walter et al. 2007 eq. 25.
inline double DBeckmann(double alpha, double th) {
  const double c = std::cos(th), t = std::tan(th);
  return std::exp(-(t * t) / (alpha * alpha)) / (kPi * alpha * alpha * std::pow(c, 4));
}
// Walter et al. 2007 §5.1, exact Smith G1 for Beckmann: a = 1 / (alpha tan theta),
// G1 = 2 / (1 + erf(a) + exp(-a^2) / (a sqrt(pi))).
inline double G1Beckmann(double alpha, double theta) {
  if (theta == 0.0) return 1.0;
  const double a = 1.0 / (alpha * std::tan(theta));
  return 2.0 / (1.0 + std::erf(a) + std::exp(-a * a) / (a * std::sqrt(kPi)));
}
// Schlick 1994, from the angle: 1 - cos(t) = 2 sin^2(t / 2).
inline double OneMinusCos(double t) {
  return 2.0 * std::pow(std::sin(0.5 * t), 2);
}
inline double FSchlick(double f0, double t) {
  return f0 + (1.0 - f0) * std::pow(OneMinusCos(t), 5);
}

// Fresnel equations in the s/p amplitude form with Snell's law (as in mebiusbox 2018 eqs.
// 32-34, 38): light in medium 1 (eta1 = 1) hits medium 2.
inline double FDielectricSnell(double eta, double theta1) {
  const double theta2 = std::asin(std::sin(theta1) / eta);
  const double c1 = std::cos(theta1), c2 = std::cos(theta2);
  const double r_par = (eta * c1 - c2) / (eta * c1 + c2);
  const double r_perp = (c1 - eta * c2) / (c1 + eta * c2);
  return 0.5 * (r_par * r_par + r_perp * r_perp);
}
// Fresnel equations with a complex index n = eta + i k (Born & Wolf §14.2), std::complex.
inline double FConductorComplex(double eta, double k, double theta) {
  const std::complex<double> n(eta, k);
  const double c = std::cos(theta), s = std::sin(theta);
  const std::complex<double> root = std::sqrt(n * n - s * s);
  const std::complex<double> rs = (c - root) / (c + root);
  const std::complex<double> rp = (n * n * c - root) / (n * n * c + root);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

// ---- models ----------------------------------------------------------------------------------

inline void Lambert(const double* p, const Angles&, double rgb[3]) {
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] / kPi;
}

// Oren & Nayar 1994 eq. 30, in angles.
inline void OrenNayar(const double* p, const Angles& a, double rgb[3]) {
  const double s2 = p[3] * p[3];
  const double A = 1.0 - 0.5 * s2 / (s2 + 0.33), B = 0.45 * s2 / (s2 + 0.09);
  const double alpha = std::max(a.ti, a.to), beta = std::min(a.ti, a.to);
  const double v = A + B * std::max(0.0, std::cos(a.po - a.pi)) * std::sin(alpha) * std::tan(beta);
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] / kPi * v;
}

// Fujii 2012's improved Oren-Nayar, in angles: s = sin(th_i) sin(th_o) cos(ph_i - ph_o).
inline void OrenNayarFujii(const double* p, const Angles& a, double rgb[3]) {
  const double sigma = p[3];
  const double A = 1.0 / (kPi + (kPi / 2 - 2.0 / 3.0) * sigma), B = sigma * A;
  const double s = std::sin(a.ti) * std::sin(a.to) * std::cos(a.pi - a.po);
  const double t = s > 0 ? std::max(std::cos(a.ti), std::cos(a.to)) : 1.0;
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * (A + B * s / t);
}

// Burley 2012 §5.3 as published, r = sqrt(alpha), in Burley 2015's split form
// (1 - FL/2)(1 - FV/2) + RR (FL + FV + FL FV (RR - 1)), RR = 2 r cos_d^2 (Cycles' form).
inline void Burley2012(const double* p, const Angles& a, double rgb[3]) {
  const double r = std::sqrt(p[3]), cd = std::cos(Half(a).td);
  const double fl = std::pow(OneMinusCos(a.ti), 5), fv = std::pow(OneMinusCos(a.to), 5);
  const double rr = 2 * r * cd * cd;
  const double v = (1 - fl / 2) * (1 - fv / 2) + rr * (fl + fv + fl * fv * (rr - 1));
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * v / kPi;
}

// Lagarde & de Rousiers 2014 Listing 1 (Fr_DisneyDiffuse) with linearRoughness = sqrt(alpha).
inline void BurleyFrostbite(const double* p, const Angles& a, double rgb[3]) {
  const double lr = std::sqrt(p[3]);
  auto lerp = [](double x, double y, double t) { return x + (y - x) * t; };
  const double ldoth = std::cos(Half(a).td);
  const double energy_bias = lerp(0.0, 0.5, lr);
  const double energy_factor = lerp(1.0, 1.0 / 1.51, lr);
  const double fd90 = energy_bias + 2.0 * ldoth * ldoth * lr;
  auto fresnel = [](double f0, double f90, double t) {
    return f0 + (f90 - f0) * std::pow(OneMinusCos(t), 5);
  };
  const double fl = fresnel(1.0, fd90, a.ti);
  const double fv = fresnel(1.0, fd90, a.to);
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * fl * fv * energy_factor / kPi;
}

// Lewis 1994 normalized Phong, mirror direction in angles: (theta_i, phi_i + pi).
inline void Phong(const double* p, const Angles& a, double rgb[3]) {
  const double n = p[3];
  const double cos_r = std::cos(a.ti) * std::cos(a.to) +
                       std::sin(a.ti) * std::sin(a.to) * std::cos(a.po - a.pi - kPi);
  const double v = (n + 2) / (2 * kPi) * std::pow(std::max(0.0, cos_r), n);
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * v;
}

// Normalized Blinn-Phong, (n + 8) / (8 pi) (Real-Time Rendering 3rd ed. eq. 7.49).
inline void BlinnPhong(const double* p, const Angles& a, double rgb[3]) {
  const double n = p[3];
  const double v = (n + 8) / (8 * kPi) * std::pow(std::cos(Half(a).th), n);
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * v;
}

// Ward 1992 eq. 4 (duer = false) and Duer 2006 (duer = true).
inline void Ward(const double* p, const Angles& a, double rgb[3], bool duer) {
  const double alpha = p[3], t = std::tan(Half(a).th);
  const double cc = std::cos(a.ti) * std::cos(a.to);
  const double v =
      std::exp(-t * t / (alpha * alpha)) / (4 * kPi * alpha * alpha * (duer ? cc : std::sqrt(cc)));
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * v;
}

// Ward 1992 eq. 5, anisotropic, with phi_h.
inline void WardAniso(const double* p, const Angles& a, double rgb[3]) {
  const HalfAngles h = Half(a);
  const double ax = p[3], ay = p[4], t = std::tan(h.th);
  const double e = t * t * (std::pow(std::cos(h.ph) / ax, 2) + std::pow(std::sin(h.ph) / ay, 2));
  const double v = std::exp(-e) / (4 * kPi * ax * ay * std::sqrt(std::cos(a.ti) * std::cos(a.to)));
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * v;
}

// Walter 2007 eq. 20 with D eq. 33 and separable G1 eq. 34 (hc = false) or Heitz 2014 eq. 99
// height-correlated G (hc = true).
inline void Ggx(const double* p, const Angles& a, double rgb[3], bool hc) {
  const double alpha = p[3];
  const double th = Half(a).th;
  const double g = hc ? 1.0 / (1.0 + LambdaGgx(alpha, a.ti) + LambdaGgx(alpha, a.to))
                      : G1Ggx(alpha, a.ti) * G1Ggx(alpha, a.to);
  const double v = DGgx(alpha, th) * g / (4 * std::cos(a.ti) * std::cos(a.to));
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * v;
}

// The glTF-style GGX lobe with free RGB F0 (models/ggx.h "ggx-f0"): Walter 2007 eq. 20 with
// D eq. 33, Heitz 2014 eq. 99 height-correlated G and Schlick 1994 F per channel, no weight.
inline void GgxF0(const double* p, const Angles& a, double rgb[3]) {
  const double alpha = p[3];
  const HalfAngles h = Half(a);
  const double g = 1.0 / (1.0 + LambdaGgx(alpha, a.ti) + LambdaGgx(alpha, a.to));
  const double v = DGgx(alpha, h.th) * g / (4 * std::cos(a.ti) * std::cos(a.to));
  for (int c = 0; c < 3; ++c) rgb[c] = FSchlick(p[c], h.td) * v;
}

// Löw et al. 2012 smooth surface model as models/abc.h states it: A (1 + B |D_p|^2)^-C F,
// |D_p|^2 = |sin ti (cos pi, sin pi) + sin to (cos po, sin po)|^2 by the law of cosines,
// written (si - so)^2 + 4 si so cos^2(dphi / 2) so that nothing cancels near dphi = pi.
inline void Abc(const double* p, const Angles& a, double rgb[3]) {
  const double si = std::sin(a.ti), so = std::sin(a.to);
  const double dp2 =
      (si - so) * (si - so) + 4 * si * so * std::pow(std::cos(0.5 * (a.pi - a.po)), 2);
  const double v = std::pow(1 + p[3] * dp2, -p[4]) * FSchlick(p[5], Half(a).td);
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * v;
}

// Gamma(s, 1) = integral_1^inf t^(s-1) e^-t dt by Simpson's rule (4000 panels) after the
// substitution t = 1 + u^2 / (1 - u), u in [0, 1) (the integrand vanishes smoothly at u = 1).
inline double UpperGammaAt1(double s) {
  static thread_local double cached_s = 2, cached = 0;  // one p per parameter set
  if (s == cached_s) return cached;
  const int n = 4000;
  auto f = [&](double u) {
    if (u >= 1) return 0.0;
    const double t = 1 + u * u / (1 - u);
    const double dt = (2 * u - u * u) / ((1 - u) * (1 - u));
    return std::pow(t, s - 1) * std::exp(-t) * dt;
  };
  double sum = f(0) + f(1);
  for (int k = 1; k < n; ++k) sum += (k % 2 ? 4 : 2) * f(static_cast<double>(k) / n);
  cached_s = s;
  cached = sum / (3.0 * n);
  return cached;
}

// Bagher et al. 2012 SGD, D = P22(tan^2 th) / (pi cos^4 th), P22(x) = K e^(-(alpha + x)/alpha)
// / (alpha + x)^p, K = alpha^(p - 1) / Gamma(1 - p, 1) — in the paper's form (overflows for
// tiny alpha; the parameter sets stay above 1e-4).
inline double DSgd(double alpha, double pw, double th) {
  const double x = std::pow(std::tan(th), 2);
  const double k = std::pow(alpha, pw - 1) / UpperGammaAt1(1 - pw);
  return k * std::exp(-(alpha + x) / alpha) / std::pow(alpha + x, pw) /
         (kPi * std::pow(std::cos(th), 4));
}

// models/sgd.h: Walter 2007 eq. 20 with the SGD, Cook-Torrance V-groove G and Schlick F.
inline void Sgd(const double* p, const Angles& a, double rgb[3]) {
  const HalfAngles h = Half(a);
  const double ch = std::cos(h.th), cd = std::cos(h.td);
  const double g = std::min({1.0, 2 * ch * std::cos(a.to) / cd, 2 * ch * std::cos(a.ti) / cd});
  const double v =
      DSgd(p[3], p[4], h.th) * g * FSchlick(p[5], h.td) / (4 * std::cos(a.ti) * std::cos(a.to));
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * v;
}

// Estevez & Kulla 2017 Charlie D = (2 + 1/alpha) sin(th_h)^(1/alpha) / (2 pi), in the paper's
// form with std::pow, and Neubelt & Pettineo 2013's V = 1 / (4 (cos_i + cos_o - cos_i cos_o)).
inline void Sheen(const double* p, const Angles& a, double rgb[3]) {
  const double alpha = p[3];
  const double d = (2 + 1 / alpha) * std::pow(std::sin(Half(a).th), 1 / alpha) / (2 * kPi);
  const double ci = std::cos(a.ti), co = std::cos(a.to);
  const double v = d / (4 * (ci + co - ci * co));
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * v;
}

// Walter 2007 eq. 20 with D eq. 25 and exact separable Smith G.
inline void Beckmann(const double* p, const Angles& a, double rgb[3]) {
  const double alpha = p[3];
  const double v = DBeckmann(alpha, Half(a).th) * G1Beckmann(alpha, a.ti) *
                   G1Beckmann(alpha, a.to) / (4 * std::cos(a.ti) * std::cos(a.to));
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * v;
}

// Ngan et al. 2005 Cook-Torrance: ks F D G / (pi cos_i cos_o), V-groove G in half angles.
inline void CookTorrance(const double* p, const Angles& a, double rgb[3]) {
  const double alpha = p[3], f0 = p[4];
  const HalfAngles h = Half(a);
  const double ch = std::cos(h.th), cd = std::cos(h.td);
  const double g = std::min({1.0, 2 * ch * std::cos(a.to) / cd, 2 * ch * std::cos(a.ti) / cd});
  const double v =
      FSchlick(f0, h.td) * DBeckmann(alpha, h.th) * g / (kPi * std::cos(a.ti) * std::cos(a.to));
  for (int c = 0; c < 3; ++c) rgb[c] = p[c] * v;
}

// Lafortune et al. 1997 in the original C-matrix form, C_x = C_y = cxy C_z with
// C_z = (rho (n + 2) / (2 pi) / sqrt(1 + cxy^(2n)))^(1/n) per channel (models/lafortune.h).
inline void Lafortune(const double* p, const Angles& a, double rgb[3]) {
  const double cxy = p[3], n = p[4];
  const V3 u = Dir(a.ti, a.pi), v = Dir(a.to, a.po);
  for (int c = 0; c < 3; ++c) {
    // sqrt(1 + |cxy|^(2n)) = |cxy|^n sqrt(1 + |cxy|^(-2n)): the second form for |cxy| > 1,
    // where |cxy|^(2n) overflows.
    const double k = p[c] * (n + 2) / (2 * kPi);
    const double cz =
        std::abs(cxy) <= 1
            ? std::pow(k / std::sqrt(1 + std::pow(cxy * cxy, n)), 1.0 / n)
            : std::pow(k / std::sqrt(1 + std::pow(cxy * cxy, -n)), 1.0 / n) / std::abs(cxy);
    const double cx = cxy * cz, cy = cxy * cz;
    const double x = cx * u.x * v.x + cy * u.y * v.y + cz * u.z * v.z;
    rgb[c] = x > 0 ? std::pow(x, n) : 0.0;
  }
}

// Karis 2013 in its printed form (also the OpenGL course 2023's): GGX with
// (n.h)^2 (a^2 - 1) + 1, k = (r + 1)^2 / 8 with roughness r = sqrt(alpha), F0 = mix(0.04, base, m).
inline void Ue4(const double* p, const Angles& a, double rgb[3]) {
  const double m = p[3], r = std::sqrt(p[4]), r4 = r * r * r * r;
  const HalfAngles h = Half(a);
  const double nh = std::cos(h.th), nl = std::cos(a.ti), nv = std::cos(a.to);
  const double denom = nh * nh * (r4 - 1.0) + 1.0;
  const double d = r4 / (kPi * denom * denom);
  const double k = (r + 1) * (r + 1) * 0.125;
  const double g = nl / (nl * (1 - k) + k) * nv / (nv * (1 - k) + k);
  for (int c = 0; c < 3; ++c) {
    const double f0 = 0.04 + (p[c] - 0.04) * m;
    const double f = FSchlick(f0, h.td);
    rgb[c] = p[c] / kPi * (1 - m) + d * g * f / (4 * nl * nv);
  }
}

}  // namespace brdfit::oracle
