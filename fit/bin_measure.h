// Measure of a table cell in (wi, wo) space: how much of the pair-of-hemispheres domain a cell
// stands for. Fit losses and metrics weight each cell by it so that the result does not depend
// on how finely the grid happens to be binned (MERL's theta_h bins shrink towards the
// highlight).
#pragma once

#include "core/table.h"

namespace brdfit {

// Derivation (checked in tests/fit/test_samples.cc):
//  For fixed wi, wo = 2 (wi.h) h - wi gives dwo = 4 (wi.h) dwh (Torrance & Sparrow 1967;
//  Walter et al. 2007, eq. 14), and rotating wi into the frame of h is measure preserving, so
//      dwi dwo = 4 cos(theta_d) dwh dwd
//              = 4 cos(theta_d) sin(theta_h) dtheta_h dphi_h sin(theta_d) dtheta_d dphi_d.
//  An isotropic table does not depend on phi_h; integrating it over [0, 2 pi) and the cell's
//  box gives a product of one-dimensional integrals:
//      w = 2 pi * 4 * [cos th_lo - cos th_hi] * [(sin^2 td_hi - sin^2 td_lo) / 2] * dphi_d.
//  This is the exact integral over the bin (the midpoint rule,
//  2 pi 4 cos td sin th dth sin td dtd dphi_d, agrees with it to second order in the bin
//  widths). Cells are not clipped at the horizon. Totals (tested): over all cells exactly
//  4 pi^2 (pairs whose half vector is above the surface, phi_d folded); over the cells above
//  the horizon about 2 pi^2, half of the (2 pi)^2 of ordered pairs of directions, because the
//  fold counts each unordered pair {wi, wo} once.
double CellMeasure(const Grid& grid, int ih, int id, int ip);

}  // namespace brdfit
