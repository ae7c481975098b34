#include "fit/sample_plan.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "fit/bin_measure.h"

namespace brdfit {

namespace {

// Cells whose directions are this close to the horizon are dropped whatever the cut-off
// (the masking terms divide by cos theta).
constexpr double kMinCos = 1e-3;

}  // namespace

AxisTrig MakeAxisTrig(const Grid& g) {
  AxisTrig t;
  auto fill = [](int n, auto angle_at, std::vector<double>* s, std::vector<double>* c) {
    s->resize(n);
    c->resize(n);
    for (int i = 0; i < n; ++i) {
      const double a = angle_at(i + 0.5);
      (*s)[i] = std::sin(a);
      (*c)[i] = std::cos(a);
    }
  };
  fill(g.n_theta_h, [&](double x) { return g.ThetaHAt(x); }, &t.sin_h, &t.cos_h);
  fill(g.n_theta_d, [&](double x) { return g.ThetaDAt(x); }, &t.sin_d, &t.cos_d);
  fill(g.n_phi_d, [&](double x) { return g.PhiDAt(x); }, &t.sin_p, &t.cos_p);
  return t;
}

std::size_t SamplePlan::Bytes() const {
  return sizeof(std::uint32_t) * (row_begin.size() + unit_begin.size() + cell.size()) +
         sizeof(double) * (row_weight.size() + cos_i.size());
}

void ForEachPlanRow(const Grid& g, const SampleOptions& options, const AxisTrig& t,
                    const PlanRowFn& fn) {
  if (!(options.cutoff_deg > 0.0 && options.cutoff_deg <= 90.0)) {
    throw InputError("angle cut-off must be in (0, 90] degrees, got " +
                     std::to_string(options.cutoff_deg));
  }
  const double cos_cut = std::max(std::cos(options.cutoff_deg * kPi / 180.0), kMinCos);
  const bool pair = options.pair_mirrors;
  const int half = pair ? (g.n_phi_d + 1) / 2 : g.n_phi_d;
  std::vector<std::uint32_t> unit_begin, cell;
  std::vector<double> cos_i;
  for (int ih = 0; ih < g.n_theta_h; ++ih) {
    for (int id = 0; id < g.n_theta_d; ++id) {
      unit_begin.assign(1, 0);
      cell.clear();
      cos_i.clear();
      for (int ip = 0; ip < half; ++ip) {
        // cos theta_i and cos theta_o at the centre, as CentreDirections computes wi.z and wo.z
        // up to rounding: the inside test of the cut-off.
        const double ci = t.cos_h[ih] * t.cos_d[id] - t.sin_h[ih] * t.sin_d[id] * t.cos_p[ip];
        const double co = 2.0 * t.cos_d[id] * t.cos_h[ih] - ci;
        if (!(ci >= cos_cut && co >= cos_cut)) continue;
        Vec3 wi, wo;
        CentreDirections(t, ih, id, ip, &wi, &wo);
        cell.push_back(static_cast<std::uint32_t>(g.Index(ih, id, ip)));
        cos_i.push_back(wi.z);
        const int mirror = g.n_phi_d - 1 - ip;
        if (pair && mirror != ip) {
          cell.push_back(static_cast<std::uint32_t>(g.Index(ih, id, mirror)));
          cos_i.push_back(wo.z);  // the mirror's theta_i is the unit's theta_o
        }
        unit_begin.push_back(static_cast<std::uint32_t>(cell.size()));
      }
      PlanRow row;
      row.ih = ih;
      row.id = id;
      row.weight = options.weighting == Weighting::kBinMeasure ? CellMeasure(g, ih, id, 0) : 1.0;
      row.units = unit_begin.size() - 1;
      row.unit_begin = unit_begin.data();
      row.cell = cell.data();
      row.cos_i = cos_i.data();
      fn(row);
    }
  }
}

void ForEachPlanRow(const SamplePlan& p, const PlanRowFn& fn) {
  const int n_d = p.key.grid.n_theta_d;
  for (std::size_t r = 0; r + 1 < p.row_begin.size(); ++r) {
    PlanRow row;
    row.ih = static_cast<int>(r / n_d);
    row.id = static_cast<int>(r % n_d);
    row.weight = p.row_weight[r];
    row.units = p.row_begin[r + 1] - p.row_begin[r];
    row.unit_begin = &p.unit_begin[p.row_begin[r]];
    row.cell = p.cell.data();
    row.cos_i = p.cos_i.data();
    fn(row);
  }
}

SamplePlan MakeSamplePlan(const Grid& g, const SampleOptions& options) {
  SamplePlan p;
  p.key = SamplePlanKey::Of(g, options);
  p.trig = MakeAxisTrig(g);
  const std::size_t rows = static_cast<std::size_t>(g.n_theta_h) * g.n_theta_d;
  p.row_begin.reserve(rows + 1);
  p.row_weight.reserve(rows);
  // Upper bounds (every cell inside): reserved pages that are never written take no memory,
  // and no array is copied by growth.
  const int half = options.pair_mirrors ? (g.n_phi_d + 1) / 2 : g.n_phi_d;
  p.unit_begin.reserve(rows * static_cast<std::size_t>(half) + 1);
  p.cell.reserve(g.NumCells());
  p.cos_i.reserve(g.NumCells());
  p.unit_begin.push_back(0);
  ForEachPlanRow(g, options, p.trig, [&](const PlanRow& row) {
    p.row_begin.push_back(static_cast<std::uint32_t>(p.NumUnits()));
    p.row_weight.push_back(row.weight);
    for (std::size_t k = 0; k < row.units; ++k) {
      for (std::uint32_t m = row.unit_begin[k]; m < row.unit_begin[k + 1]; ++m) {
        p.cell.push_back(row.cell[m]);
        p.cos_i.push_back(row.cos_i[m]);
      }
      p.unit_begin.push_back(static_cast<std::uint32_t>(p.cell.size()));
    }
  });
  p.row_begin.push_back(static_cast<std::uint32_t>(p.NumUnits()));
  return p;
}

}  // namespace brdfit
