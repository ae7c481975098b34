// Adaptive Gauss-Kronrod (7-15) quadrature for the physics tests (NDF normalization, Smith
// masking identity, white furnace). Sharp lobes (alpha = 0.01, n = 1e4) are resolved by
// splitting the polar range at geometric breakpoints before adapting.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace brdfit::test {

// One G7-K15 panel: returns the Kronrod estimate and |Kronrod - Gauss| in *err.
template <class F>
double GaussKronrod15(const F& f, double a, double b, double* err) {
  // Nodes and weights of the 15-point Kronrod rule and its embedded 7-point Gauss rule
  // (Piessens et al., QUADPACK, 1983; qk15.f).
  static constexpr std::array<double, 8> xgk = {
      0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
      0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
      0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
      0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
  static constexpr std::array<double, 8> wgk = {
      0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
      0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
      0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
      0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
  static constexpr std::array<double, 4> wg = {
      0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
      0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double k = wgk[7] * fc, g = wg[3] * fc;
  for (int j = 0; j < 7; ++j) {
    const double f1 = f(c - h * xgk[j]), f2 = f(c + h * xgk[j]);
    k += wgk[j] * (f1 + f2);
    if (j % 2 == 1) g += wg[j / 2] * (f1 + f2);
  }
  *err = std::abs((k - g) * h);
  return k * h;
}

// Adaptive bisection until each panel's error estimate is below its share of tol, or below
// 1e-10 of its own value (integrands spanning hundreds of decades, e.g. Lafortune lobes with
// n = 5000), or 30 bisections deep.
template <class F>
double Integrate(const F& f, double a, double b, double tol, int depth = 0) {
  double err = 0;
  const double v = GaussKronrod15(f, a, b, &err);
  if (err <= tol || err <= 1e-10 * std::abs(v) || depth >= 30) return v;
  const double m = 0.5 * (a + b);
  return Integrate(f, a, m, 0.5 * tol, depth + 1) + Integrate(f, m, b, 0.5 * tol, depth + 1);
}

// Integrate over [a, b] split at the given interior breakpoints (sorted, inside (a, b)).
template <class F>
double IntegrateSplit(const F& f, const std::vector<double>& points, double tol) {
  double sum = 0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    sum += Integrate(f, points[i], points[i + 1], tol / (points.size() - 1));
  }
  return sum;
}

// Breakpoints for a polar angle in [0, pi/2] with features near 0 of width down to 1e-4.
inline std::vector<double> PolarBreakpoints() {
  return {0.0, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3, 0.7, 1.2, M_PI / 2};
}

}  // namespace brdfit::test
