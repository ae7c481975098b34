#include "fit/samples.h"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <cmath>
#include <stdexcept>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/error.h"
#include "core/sse2_finite.h"
#include "fit/bin_measure.h"
#include "fit/loss.h"
#include "fit/sample_geometry.h"
#include "fit/sample_plan.h"
#include "fit/stratified.h"

namespace brdfit {

namespace {

// Random budgets spread samples as W_s^0.5 over theta_h strata (see SelectStratified): the
// highlight's bins are tiny in measure but decide alpha. Measured in bench/bench_fit.cc.
constexpr double kAllocationPower = 0.5;

bool ParseCount(const std::string& s, std::size_t* out) {
  if (s.empty()) return false;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && ptr == s.data() + s.size();
}

struct UnitAxes {
  int ih, id, ip;
};

// The stride a stride:K budget applies: K, or the number of phi_d bins in [0, pi/2) when K is
// larger (small grids), so that every row keeps a bin (and, unpaired, its mirror) rather than
// none.
int EffectiveStride(const Budget& b, const Grid& g) {
  return std::min(b.stride, std::max((g.n_phi_d + 1) / 2, 1));
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

// Per cell of the table: usable (valid with finite values) and negative (some channel < 0).
constexpr std::uint8_t kUsable = 1, kNegative = 2;

// Bit k of the result: x[k] is finite (k < 6); of *negative: x[k] < 0. Six values (two cells)
// with SSE2 compares (core/sse2_finite.h).
#if defined(__SSE2__)
int FiniteAndNegativeBits6(const double* x, int* negative) {
  const __m128d zero = _mm_setzero_pd();
  int finite = 0, neg = 0;
  for (int k = 0; k < 3; ++k) {
    const __m128d v = _mm_loadu_pd(x + 2 * k);
    finite |= _mm_movemask_pd(FiniteLanes(v)) << (2 * k);
    neg |= _mm_movemask_pd(_mm_cmplt_pd(v, zero)) << (2 * k);
  }
  *negative = neg;
  return finite;
}
#endif

// The table's usable cells, and the counts that depend only on the table: valid, non-finite.
std::vector<std::uint8_t> UsableCells(const Table& table, SampleCounts* c,
                                      std::size_t* n_usable) {
  const std::size_t n = table.grid.NumCells();
  std::vector<std::uint8_t> flags(n);
  std::size_t valid = 0, nonfinite = 0;
  // Cell i from its validity and its three channels' bits (finite: all set; negative: any set).
  auto set = [&](std::size_t i, bool all_finite, bool any_negative) {
    const bool ok = table.valid[i] != 0;
    valid += ok;
    nonfinite += ok && !all_finite;
    flags[i] = static_cast<std::uint8_t>((ok && all_finite ? kUsable : 0) |
                                         (ok && all_finite && any_negative ? kNegative : 0));
  };
  std::size_t i = 0;
#if defined(__SSE2__)
  for (; i + 2 <= n; i += 2) {
    int neg = 0;
    const int fin = FiniteAndNegativeBits6(&table.rgb[3 * i], &neg);
    set(i, (fin & 7) == 7, (neg & 7) != 0);
    set(i + 1, (fin & 070) == 070, (neg & 070) != 0);
  }
#endif
  for (; i < n; ++i) {
    const double* v = &table.rgb[3 * i];
    set(i, std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]),
        v[0] < 0 || v[1] < 0 || v[2] < 0);
  }
  c->valid = valid;
  c->nonfinite = nonfinite;
  *n_usable = valid - nonfinite;
  return flags;
}

// Every usable cell of the table inside the cut-off (options.budget is not applied here):
// the plan's units in order (`visit_rows(fn)` calls fn on every PlanRow), each with the members
// the table's mask keeps; a unit with none is no sample. Every valid, finite cell is either kept
// here or beyond the cut-off.
template <class VisitRows>
Samples ApplyPlan(const Table& table, const SampleOptions& options, const AxisTrig& trig,
                  const VisitRows& visit_rows, GeometryStorage storage, bool copy_values) {
  const Grid& g = table.grid;
  if (table.rgb.size() != 3 * g.NumCells() || table.valid.size() != g.NumCells()) {
    throw InputError(table.provenance.source, "table arrays do not match its grid");
  }
  Samples out;
  out.grid = g;
  out.options = options;
  out.counts.cells = g.NumCells();
  out.trig = trig;
  std::size_t n_usable = 0;
  const std::vector<std::uint8_t> flags = UsableCells(table, &out.counts, &n_usable);
  const bool stored = storage == GeometryStorage::kStored;
  // Room for every usable cell: the pages of it never written take no memory (a table without
  // holes fills it), and no array is copied by growth (a full MERL table has 1.1 M
  // observations).
  const std::size_t n_obs = n_usable, n_samples = n_usable;
  out.cell.reserve(n_obs);
  if (copy_values) out.value.reserve(3 * n_obs);
  out.weight.reserve(n_obs);
  out.cos_i.reserve(n_obs);
  if (stored) out.geometry.reserve(n_samples);
  out.obs_begin.reserve(n_samples + 1);
  out.obs_begin.push_back(0);
  std::size_t negative = 0;
  visit_rows([&](const PlanRow& row) {
    const double w_cell = row.weight;
    for (std::size_t k = 0; k < row.units; ++k) {
      const std::size_t before = out.cell.size();
      for (std::uint32_t m = row.unit_begin[k]; m < row.unit_begin[k + 1]; ++m) {
        const std::uint32_t idx = row.cell[m];
        const std::uint8_t f = flags[idx];
        if (!(f & kUsable)) continue;
        out.cell.push_back(idx);
        if (copy_values) {
          const double* v = table.Value(idx);
          out.value.insert(out.value.end(), v, v + 3);
        }
        negative += (f & kNegative) != 0;
        out.weight.push_back(w_cell);
        out.total_weight += w_cell;
        out.cos_i.push_back(row.cos_i[m]);
      }
      if (out.cell.size() == before) continue;
      if (stored) {
        // The unit's first member is its first-half cell (plan order).
        const int ip =
            static_cast<int>(row.cell[row.unit_begin[k]] - g.Index(row.ih, row.id, 0));
        out.geometry.push_back(CentreGeometry(out.trig, row.ih, row.id, ip));
      }
      out.obs_begin.push_back(static_cast<std::uint32_t>(out.cell.size()));
    }
  });
  out.counts.negative = negative;
  out.counts.eligible = out.cell.size();
  out.counts.beyond_cutoff = n_usable - out.counts.eligible;
  out.counts.selected = out.cell.size();
  return out;
}

// From a stored plan, or (plan null) from the rows computed on the fly.
Samples ApplyPlan(const SamplePlan* plan, const Table& table, const SampleOptions& options,
                  GeometryStorage storage, bool copy_values) {
  if (plan) {
    return ApplyPlan(
        table, options, plan->trig, [&](const PlanRowFn& fn) { ForEachPlanRow(*plan, fn); },
        storage, copy_values);
  }
  const AxisTrig trig = MakeAxisTrig(table.grid);
  return ApplyPlan(
      table, options, trig,
      [&](const PlanRowFn& fn) { ForEachPlanRow(table.grid, options, trig, fn); }, storage,
      copy_values);
}

void CheckPlan(const SamplePlan& plan, const Table& table, const SampleOptions& options) {
  if (!plan.Matches(table.grid, options)) {
    throw std::invalid_argument("sample plan made for another grid or other sample options");
  }
}

// PrepareSamples of a stored plan or (plan null) of rows computed on the fly.
Samples PrepareFrom(const SamplePlan* plan, const Table& table, const SampleOptions& options,
                    GeometryStorage storage) {
  if (options.budget.kind == Budget::Kind::kFull) {
    return ApplyPlan(plan, table, options, storage, true);
  }
  // A sub-sampled budget: the samples SelectBudget keeps of the full set (one selection rule
  // for the fitter, which selects from its metric set, and for direct preparation).
  SampleOptions full = options;
  full.budget = Budget{};
  Samples out = SelectBudget(ApplyPlan(plan, table, full, GeometryStorage::kOnDemand, true),
                             options.budget, options.seed);
  if (storage == GeometryStorage::kOnDemand) out.geometry = {};
  return out;
}

Samples MetricFrom(const SamplePlan* plan, Table&& table, const SampleOptions& options) {
  SampleOptions full = options;
  full.budget = Budget{};
  Samples out = ApplyPlan(plan, table, full, GeometryStorage::kOnDemand, false);
  out.table_rgb = std::move(table.rgb);
  table = Table{};
  return out;
}

}  // namespace

Samples PrepareSamples(const Table& table, const SampleOptions& options, GeometryStorage storage) {
  return PrepareFrom(nullptr, table, options, storage);
}

Samples PrepareSamples(const Table& table, const SamplePlan& plan, const SampleOptions& options,
                       GeometryStorage storage) {
  CheckPlan(plan, table, options);
  return PrepareFrom(&plan, table, options, storage);
}

Samples PrepareMetricSamples(Table&& table, const SampleOptions& options) {
  return MetricFrom(nullptr, std::move(table), options);
}

Samples PrepareMetricSamples(Table&& table, const SamplePlan& plan, const SampleOptions& options) {
  CheckPlan(plan, table, options);
  return MetricFrom(&plan, std::move(table), options);
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
  ForEachSampleAxes(samples, 0, samples.NumSamples(),
                    [&](std::size_t s, int ih, int, int) { stratum[s] = ih; });
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
  const UnitAxes a = PrimaryAxes(samples, s);
  return CentreGeometry(samples.trig, a.ih, a.id, a.ip);
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
    // Rows are runs of consecutive samples of one (theta_h, theta_d); weights summed in order.
    std::vector<std::size_t> row_kept;
    double all = 0, sel = 0;
    int row_ih = -1, row_id = -1;
    auto end_row = [&] {
      for (std::size_t s : row_kept) {
        kept.push_back(s);
        factor.push_back(all / sel);
      }
      row_kept.clear();
      all = sel = 0;
    };
    ForEachSampleAxes(full, 0, ns, [&](std::size_t s, int ih, int id, int ip) {
      if (ih != row_ih || id != row_id) {
        end_row();
        row_ih = ih;
        row_id = id;
      }
      all += weight[s];
      if (ip % stride == offset) {
        sel += weight[s];
        row_kept.push_back(s);
      }
    });
    end_row();
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
