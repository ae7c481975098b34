#include "fit/samples.h"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <cmath>

#include "core/error.h"
#include "fit/bin_measure.h"
#include "fit/loss.h"
#include "fit/stratified.h"

namespace brdfit {

namespace {

// Cells whose directions are this close to the horizon are dropped whatever the cut-off
// (the masking terms divide by cos theta).
constexpr double kMinCos = 1e-3;

// Random budgets spread samples as W_s^0.5 over theta_h strata (see SelectStratified): the
// highlight's bins are tiny in measure but decide alpha. Measured in bench/bench_fit.cc.
constexpr double kAllocationPower = 0.5;

bool ParseCount(const std::string& s, std::size_t* out) {
  if (s.empty()) return false;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && ptr == s.data() + s.size();
}

// A sample before it is appended: a cell and its optional phi_d mirror.
struct Unit {
  std::uint32_t primary;   // table index of (ih, id, ip), ip in the first half (member or not)
  std::uint32_t cells[2];  // the members: the primary cell and/or its mirror, whichever are usable
  std::uint8_t members;
};

struct UnitAxes {
  int ih, id, ip;
};

// The stride a stride:K budget applies: K, or the number of phi_d bins in [0, pi/2) when K is
// larger (small grids), so that every row keeps a bin (and, unpaired, its mirror) rather than
// none.
int EffectiveStride(const Budget& b, const Grid& g) {
  return std::min(b.stride, std::max((g.n_phi_d + 1) / 2, 1));
}

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

// The geometry at the centre of cell (ih, id, ip): the same operations as
// FromHalfDiff(CellCentre(ih, id, ip), phi_h = 0), from the axis tables (bit-identical; tested).
Geometry GeometryAt(const AxisTrig& t, const UnitAxes& a) {
  const Vec3 d{t.sin_d[a.id] * t.cos_p[a.ip], t.sin_d[a.id] * t.sin_p[a.ip], t.cos_d[a.id]};
  const Vec3 wi{t.cos_h[a.ih] * d.x + t.sin_h[a.ih] * d.z, d.y,
                -t.sin_h[a.ih] * d.x + t.cos_h[a.ih] * d.z};
  const Vec3 h{t.sin_h[a.ih], 0.0, t.cos_h[a.ih]};
  const Vec3 wo = 2.0 * Dot(wi, h) * h - wi;
  return MakeGeometry(wi, wo);
}

}  // namespace

Budget Budget::Parse(const std::string& text) {
  Budget b;
  if (text == "full") return b;
  const auto colon = text.find(':');
  const std::string head = text.substr(0, colon);
  std::size_t value = 0;
  if (colon != std::string::npos && ParseCount(text.substr(colon + 1), &value) && value >= 1) {
    if (head == "stride") {
      b.kind = Kind::kStride;
      b.stride = static_cast<int>(std::min<std::size_t>(value, 1u << 20));
      return b;
    }
    if (head == "random") {
      b.kind = Kind::kRandom;
      b.count = value;
      return b;
    }
  }
  throw InputError("bad sample budget '" + text +
                   "' (expected full, stride:K or random:N with K, N >= 1)");
}

std::string Budget::ToString() const {
  switch (kind) {
    case Kind::kFull:
      return "full";
    case Kind::kStride:
      return "stride:" + std::to_string(stride);
    case Kind::kRandom:
      return "random:" + std::to_string(count);
  }
  return "full";
}

namespace {

// Visits, in (theta_h, theta_d, phi_d) order, every unit with at least one usable member:
// fn(unit, w_cell) with w_cell the members' common cell weight. Counts what it drops and keeps
// into *counts when counts is not null.
template <class Fn>
void ForEachUnit(const Table& table, const SampleOptions& options, const AxisTrig& t,
                 SampleCounts* counts, Fn fn) {
  const Grid& g = table.grid;
  SampleCounts none;
  SampleCounts& c = counts ? *counts : none;
  const double cos_cut = std::max(std::cos(options.cutoff_deg * kPi / 180.0), kMinCos);
  const bool pair = options.pair_mirrors;
  const int half = pair ? (g.n_phi_d + 1) / 2 : g.n_phi_d;
  for (int ih = 0; ih < g.n_theta_h; ++ih) {
    for (int id = 0; id < g.n_theta_d; ++id) {
      const double w_cell =
          options.weighting == Weighting::kBinMeasure ? CellMeasure(g, ih, id, 0) : 1.0;
      for (int ip = 0; ip < half; ++ip) {
        // wi = R_y(theta_h) d with d = (sd cp, sd sp, cd); wo mirrors wi about h (geometry.h).
        const double ci = t.cos_h[ih] * t.cos_d[id] - t.sin_h[ih] * t.sin_d[id] * t.cos_p[ip];
        const double co = 2.0 * t.cos_d[id] * t.cos_h[ih] - ci;
        const bool inside = ci >= cos_cut && co >= cos_cut;
        Unit u{static_cast<std::uint32_t>(g.Index(ih, id, ip)), {0, 0}, 0};
        const int mirror = g.n_phi_d - 1 - ip;
        const int n_members = (pair && mirror != ip) ? 2 : 1;
        for (int m = 0; m < n_members; ++m) {
          const std::size_t idx = g.Index(ih, id, m == 0 ? ip : mirror);
          if (!table.valid[idx]) continue;
          ++c.valid;
          const double* v = table.Value(idx);
          if (!(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]))) {
            ++c.nonfinite;
            continue;
          }
          if (!inside) {
            ++c.beyond_cutoff;
            continue;
          }
          ++c.eligible;
          u.cells[u.members++] = static_cast<std::uint32_t>(idx);
        }
        if (u.members > 0) fn(u, UnitAxes{ih, id, ip}, w_cell);
      }
    }
  }
}

void ReserveFor(std::size_t n_samples, std::size_t n_obs, bool stored, bool copy_values,
                Samples* out) {
  out->cell.reserve(n_obs);
  if (copy_values) out->value.reserve(3 * n_obs);
  out->weight.reserve(n_obs);
  out->cos_i.reserve(n_obs);
  if (stored) out->geometry.reserve(n_samples);
  out->obs_begin.reserve(n_samples + 1);
  out->obs_begin.push_back(0);
}

// Appends the unit as one sample, each member weighing w_cell.
void AppendUnit(const Table& table, const Unit& u, const UnitAxes& a, double w_cell, bool stored,
                bool copy_values, Samples* out) {
  const Geometry geo = GeometryAt(out->trig, a);
  if (stored) out->geometry.push_back(geo);
  for (int m = 0; m < u.members; ++m) {
    const std::uint32_t idx = u.cells[m];
    const bool is_mirror = idx != u.primary;
    out->cell.push_back(idx);
    const double* v = table.Value(idx);
    if (copy_values) out->value.insert(out->value.end(), v, v + 3);
    if (v[0] < 0 || v[1] < 0 || v[2] < 0) ++out->counts.negative;
    out->weight.push_back(w_cell);
    out->total_weight += w_cell;
    out->cos_i.push_back(is_mirror ? geo.cos_o : geo.cos_i);
  }
  out->obs_begin.push_back(static_cast<std::uint32_t>(out->cell.size()));
}

}  // namespace

namespace {

// Every usable cell (options.budget is not applied here).
Samples PrepareSamplesImpl(const Table& table, const SampleOptions& options,
                           GeometryStorage storage, bool copy_values) {
  if (!(options.cutoff_deg > 0.0 && options.cutoff_deg <= 90.0)) {
    throw InputError("angle cut-off must be in (0, 90] degrees, got " +
                     std::to_string(options.cutoff_deg));
  }
  const Grid& g = table.grid;
  if (table.rgb.size() != 3 * g.NumCells() || table.valid.size() != g.NumCells()) {
    throw InputError(table.provenance.source, "table arrays do not match its grid");
  }
  Samples out;
  out.grid = g;
  out.options = options;
  out.counts.cells = g.NumCells();
  out.trig = MakeAxisTrig(g);
  const bool stored = storage == GeometryStorage::kStored;
  // Every unit: counted first so that the arrays are exactly sized (a full MERL table has
  // 1.1 M observations: growth by doubling would hold up to twice that), then filled, with no
  // per-unit list in between (17 MB for MERL).
  std::size_t n_samples = 0, n_obs = 0;
  ForEachUnit(table, options, out.trig, &out.counts, [&](const Unit& u, const UnitAxes&, double) {
    ++n_samples;
    n_obs += u.members;
  });
  ReserveFor(n_samples, n_obs, stored, copy_values, &out);
  ForEachUnit(table, options, out.trig, nullptr,
              [&](const Unit& u, const UnitAxes& a, double w_cell) {
                AppendUnit(table, u, a, w_cell, stored, copy_values, &out);
              });
  out.counts.selected = out.cell.size();
  return out;
}

}  // namespace

Samples PrepareSamples(const Table& table, const SampleOptions& options, GeometryStorage storage) {
  if (options.budget.kind == Budget::Kind::kFull) {
    return PrepareSamplesImpl(table, options, storage, true);
  }
  // A sub-sampled budget: the samples SelectBudget keeps of the full set (one selection rule
  // for the fitter, which selects from its metric set, and for direct preparation).
  SampleOptions full = options;
  full.budget = Budget{};
  Samples out = SelectBudget(PrepareSamplesImpl(table, full, GeometryStorage::kOnDemand, true),
                             options.budget, options.seed);
  if (storage == GeometryStorage::kOnDemand) out.geometry = {};
  return out;
}

Samples PrepareMetricSamples(Table&& table, const SampleOptions& options) {
  SampleOptions full = options;
  full.budget = Budget{};
  Samples out = PrepareSamplesImpl(table, full, GeometryStorage::kOnDemand, false);
  out.table_rgb = std::move(table.rgb);
  table = Table{};
  return out;
}

namespace {

// The first-half phi_d bin of sample s (its unit's primary cell, member or not).
UnitAxes PrimaryAxes(const Samples& s, std::size_t sample) {
  const Grid& g = s.grid;
  UnitAxes a;
  g.Unindex(s.cell[s.obs_begin[sample]], &a.ih, &a.id, &a.ip);
  if (s.options.pair_mirrors) a.ip = std::min(a.ip, g.n_phi_d - 1 - a.ip);
  return a;
}

// A sample's weight is its unit's: the sum of its members' cell weights, in member order.
std::vector<double> SampleWeights(const Samples& samples) {
  std::vector<double> weight(samples.NumSamples(), 0.0);
  for (std::size_t s = 0; s < weight.size(); ++s) {
    for (std::uint32_t o = samples.obs_begin[s]; o < samples.obs_begin[s + 1]; ++o) {
      weight[s] += samples.weight[o];
    }
  }
  return weight;
}

// The theta_h bin of every sample: the strata of stratified selections.
std::vector<int> ThetaHStrata(const Samples& samples) {
  std::vector<int> stratum(samples.NumSamples());
  for (std::size_t s = 0; s < stratum.size(); ++s) stratum[s] = PrimaryAxes(samples, s).ih;
  return stratum;
}

// Copies the kept samples of `from` with their weights scaled by factor[k].
Samples CopySelected(const Samples& from, const std::vector<std::size_t>& kept,
                     const std::vector<double>& factor) {
  Samples out;
  out.grid = from.grid;
  out.options = from.options;
  out.counts = from.counts;
  out.trig = from.trig;
  out.counts.negative = 0;
  std::size_t n_obs = 0;
  for (std::size_t s : kept) n_obs += from.obs_begin[s + 1] - from.obs_begin[s];
  out.geometry.reserve(kept.size());
  out.obs_begin.reserve(kept.size() + 1);
  out.cell.reserve(n_obs);
  out.value.reserve(3 * n_obs);
  out.weight.reserve(n_obs);
  out.cos_i.reserve(n_obs);
  out.obs_begin.push_back(0);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const std::size_t s = kept[k];
    out.geometry.push_back(SampleGeometry(from, s));
    for (std::uint32_t o = from.obs_begin[s]; o < from.obs_begin[s + 1]; ++o) {
      out.cell.push_back(from.cell[o]);
      const double* v = from.Value(o);
      out.value.insert(out.value.end(), v, v + 3);
      if (v[0] < 0 || v[1] < 0 || v[2] < 0) ++out.counts.negative;
      const double w = from.weight[o] * factor[k];
      out.weight.push_back(w);
      out.total_weight += w;
      out.cos_i.push_back(from.cos_i[o]);
    }
    out.obs_begin.push_back(static_cast<std::uint32_t>(out.cell.size()));
  }
  out.counts.selected = out.cell.size();
  return out;
}

}  // namespace

Geometry SampleGeometry(const Samples& samples, std::size_t s) {
  if (!samples.geometry.empty()) return samples.geometry[s];
  return GeometryAt(samples.trig, PrimaryAxes(samples, s));
}

Samples SelectBudget(const Samples& full, const Budget& budget, std::uint64_t seed) {
  const std::size_t ns = full.NumSamples();
  const std::vector<double> weight = SampleWeights(full);
  std::vector<std::size_t> kept;
  std::vector<double> factor;
  if (budget.kind == Budget::Kind::kFull) {
    kept.resize(ns);
    for (std::size_t s = 0; s < ns; ++s) kept[s] = s;
    factor.assign(ns, 1.0);
  } else if (budget.kind == Budget::Kind::kStride) {
    if (budget.stride < 1) throw InputError("stride budget needs K >= 1");
    // phi_d bins offset, offset + K, ... of the half range; each (theta_h, theta_d) row
    // rescaled to keep its total weight. K beyond the half row (small grids) is the half row:
    // one bin per row, never none.
    const int stride = EffectiveStride(budget, full.grid);
    const int offset = stride / 2;
    std::size_t row_begin = 0;
    while (row_begin < ns) {
      const UnitAxes first = PrimaryAxes(full, row_begin);
      std::size_t row_end = row_begin;
      double all = 0, sel = 0;
      while (row_end < ns) {
        const UnitAxes a = PrimaryAxes(full, row_end);
        if (a.ih != first.ih || a.id != first.id) break;
        all += weight[row_end];
        if (a.ip % stride == offset) sel += weight[row_end];
        ++row_end;
      }
      for (std::size_t s = row_begin; s < row_end; ++s) {
        if (PrimaryAxes(full, s).ip % stride == offset) {
          kept.push_back(s);
          factor.push_back(all / sel);
        }
      }
      row_begin = row_end;
    }
  } else {
    if (budget.count < 1) throw InputError("random budget needs N >= 1");
    Selection sel =
        SelectStratified(ThetaHStrata(full), weight, budget.count, seed, kAllocationPower);
    kept = std::move(sel.kept);
    factor = std::move(sel.factor);
  }
  Samples out = CopySelected(full, kept, factor);
  out.options.budget = budget;
  out.options.seed = seed;
  return out;
}

Samples Subsample(const Samples& samples, std::size_t n, std::uint64_t seed) {
  const Selection sel =
      SelectStratified(ThetaHStrata(samples), SampleWeights(samples), n, seed, kAllocationPower);
  return CopySelected(samples, sel.kept, sel.factor);
}

std::vector<double> ExpandToObservations(const Samples& samples,
                                         const std::vector<double>& per_sample_rgb) {
  assert(per_sample_rgb.size() == 3 * samples.NumSamples());
  std::vector<double> out(3 * samples.NumObservations());
  for (std::size_t s = 0; s < samples.NumSamples(); ++s) {
    for (std::uint32_t o = samples.obs_begin[s]; o < samples.obs_begin[s + 1]; ++o) {
      for (int c = 0; c < 3; ++c) out[3 * o + c] = per_sample_rgb[3 * s + c];
    }
  }
  return out;
}

}  // namespace brdfit
