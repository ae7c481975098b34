// The geometry of a run of samples, for loops over a whole set (the metric pass's predictions):
// SampleGeometry's values, with the cell index arithmetic of the on-demand geometry done once
// per (theta_h, theta_d) row instead of two integer divisions per sample.
#pragma once

#include <algorithm>
#include <cstddef>

#include "fit/sample_plan.h"
#include "fit/samples.h"
#include "models/geometry.h"

namespace brdfit {

// fn(s, ih, id, ip) for s in [begin, end): the first-half phi_d bin of sample s's unit (its
// primary cell, member or not), as SampleGeometry uses. Samples of a set are in
// (theta_h, theta_d, phi_d) order; a sample out of that order is unindexed on its own.
template <class Fn>
void ForEachSampleAxes(const Samples& samples, std::size_t begin, std::size_t end, Fn fn) {
  const Grid& g = samples.grid;
  const std::size_t n_p = static_cast<std::size_t>(g.n_phi_d);
  std::size_t row_base = 0;
  int ih = 0, id = 0, ip = 0;
  bool in_row = false;
  for (std::size_t s = begin; s < end; ++s) {
    const std::size_t c = samples.cell[samples.obs_begin[s]];
    if (!in_row || c < row_base || c >= row_base + n_p) {
      g.Unindex(c, &ih, &id, &ip);
      row_base = c - static_cast<std::size_t>(ip);
      in_row = true;
    }
    ip = static_cast<int>(c - row_base);
    if (samples.options.pair_mirrors) ip = std::min(ip, g.n_phi_d - 1 - ip);
    fn(s, ih, id, ip);
  }
}

// fn(s, SampleGeometry(samples, s)) for s in [begin, end), the same values bit for bit.
template <class Fn>
void ForEachSampleGeometry(const Samples& samples, std::size_t begin, std::size_t end, Fn fn) {
  if (!samples.geometry.empty()) {
    for (std::size_t s = begin; s < end; ++s) fn(s, samples.geometry[s]);
    return;
  }
  ForEachSampleAxes(samples, begin, end, [&](std::size_t s, int ih, int id, int ip) {
    fn(s, CentreGeometry(samples.trig, ih, id, ip));
  });
}

}  // namespace brdfit
