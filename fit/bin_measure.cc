#include "fit/bin_measure.h"

#include <cmath>

namespace brdfit {

double CellMeasure(const Grid& grid, int ih, int id, int /*ip*/) {
  const double th_lo = grid.ThetaHAt(ih), th_hi = grid.ThetaHAt(ih + 1.0);
  const double td_lo = grid.ThetaDAt(id), td_hi = grid.ThetaDAt(id + 1.0);
  const double dphi = kPi / grid.n_phi_d;
  const double s_lo = std::sin(td_lo), s_hi = std::sin(td_hi);
  // cos a - cos b = 2 sin((a+b)/2) sin((b-a)/2): no cancellation for the tiny first MERL bins.
  const double h_int = 2.0 * std::sin(0.5 * (th_lo + th_hi)) * std::sin(0.5 * (th_hi - th_lo));
  const double d_int = 0.5 * (s_hi - s_lo) * (s_hi + s_lo);
  return 2.0 * kPi * 4.0 * h_int * d_int * dphi;
}

}  // namespace brdfit
