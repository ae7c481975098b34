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

// A sample before selection: a cell and its optional phi_d mirror.
// 24 bytes: a full MERL table has 729,000 of them alive while its samples are built.
struct Unit {
  std::uint32_t primary;   // table index of (ih, id, ip), ip in the first half (member or not)
  std::uint32_t cells[2];  // the members: the primary cell and/or its mirror, whichever are usable
  std::uint8_t members;
  double weight;  // sum of the members' cell weights
};

struct UnitAxes {
  int ih, id, ip;
};

UnitAxes AxesOf(const Grid& g, const Unit& u) {
  UnitAxes a;
  g.Unindex(u.primary, &a.ih, &a.id, &a.ip);
  return a;
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

Samples PrepareSamples(const Table& table, const SampleOptions& options) {
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

  // Per-axis trigonometry at cell centres (docs/conventions.md: centre = index + 0.5).
  std::vector<double> sh(g.n_theta_h), ch(g.n_theta_h), sd(g.n_theta_d), cd(g.n_theta_d);
  std::vector<double> sp(g.n_phi_d), cp(g.n_phi_d);
  for (int i = 0; i < g.n_theta_h; ++i) {
    const double t = g.ThetaHAt(i + 0.5);
    sh[i] = std::sin(t);
    ch[i] = std::cos(t);
  }
  for (int i = 0; i < g.n_theta_d; ++i) {
    const double t = g.ThetaDAt(i + 0.5);
    sd[i] = std::sin(t);
    cd[i] = std::cos(t);
  }
  for (int i = 0; i < g.n_phi_d; ++i) {
    const double t = g.PhiDAt(i + 0.5);
    sp[i] = std::sin(t);
    cp[i] = std::cos(t);
  }
  const double cos_cut = std::max(std::cos(options.cutoff_deg * kPi / 180.0), kMinCos);
  const bool pair = options.pair_mirrors;
  const int half = pair ? (g.n_phi_d + 1) / 2 : g.n_phi_d;

  std::vector<Unit> units;
  units.reserve(static_cast<std::size_t>(g.n_theta_h) * g.n_theta_d * half);
  for (int ih = 0; ih < g.n_theta_h; ++ih) {
    for (int id = 0; id < g.n_theta_d; ++id) {
      const double w_cell =
          options.weighting == Weighting::kBinMeasure ? CellMeasure(g, ih, id, 0) : 1.0;
      for (int ip = 0; ip < half; ++ip) {
        // wi = R_y(theta_h) d with d = (sd cp, sd sp, cd); wo mirrors wi about h (geometry.h).
        const double ci = ch[ih] * cd[id] - sh[ih] * sd[id] * cp[ip];
        const double co = 2.0 * cd[id] * ch[ih] - ci;
        const bool inside = ci >= cos_cut && co >= cos_cut;
        Unit u{static_cast<std::uint32_t>(g.Index(ih, id, ip)), {0, 0}, 0, 0.0};
        const int mirror = g.n_phi_d - 1 - ip;
        const int n_members = (pair && mirror != ip) ? 2 : 1;
        for (int m = 0; m < n_members; ++m) {
          const std::size_t idx = g.Index(ih, id, m == 0 ? ip : mirror);
          if (!table.valid[idx]) continue;
          ++out.counts.valid;
          const double* v = table.Value(idx);
          if (!(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]))) {
            ++out.counts.nonfinite;
            continue;
          }
          if (!inside) {
            ++out.counts.beyond_cutoff;
            continue;
          }
          ++out.counts.eligible;
          u.cells[u.members++] = static_cast<std::uint32_t>(idx);
          u.weight += w_cell;
        }
        if (u.members > 0) units.push_back(u);
      }
    }
  }

  // Budget.
  std::vector<std::size_t> kept;
  std::vector<double> factor;
  const Budget& b = options.budget;
  if (b.kind == Budget::Kind::kFull) {
    kept.resize(units.size());
    for (std::size_t i = 0; i < units.size(); ++i) kept[i] = i;
    factor.assign(units.size(), 1.0);
  } else if (b.kind == Budget::Kind::kStride) {
    if (b.stride < 1) throw InputError("stride budget needs K >= 1");
    // Keep phi_d bins offset, offset + K, ... of the half range; rescale each (theta_h,
    // theta_d) row so that it keeps its total weight.
    const int offset = b.stride / 2;
    std::size_t row_begin = 0;
    while (row_begin < units.size()) {
      std::size_t row_end = row_begin;
      double all = 0, sel = 0;
      // Cells of one (theta_h, theta_d) row share primary / n_phi_d (core/table.h, Index).
      const std::size_t row = units[row_begin].primary / g.n_phi_d;
      while (row_end < units.size() && units[row_end].primary / g.n_phi_d == row) {
        all += units[row_end].weight;
        if (AxesOf(g, units[row_end]).ip % b.stride == offset) sel += units[row_end].weight;
        ++row_end;
      }
      for (std::size_t i = row_begin; i < row_end; ++i) {
        if (AxesOf(g, units[i]).ip % b.stride == offset) {
          kept.push_back(i);
          factor.push_back(all / sel);
        }
      }
      row_begin = row_end;
    }
  } else {
    if (b.count < 1) throw InputError("random budget needs N >= 1");
    std::vector<int> stratum(units.size());
    std::vector<double> weight(units.size());
    for (std::size_t i = 0; i < units.size(); ++i) {
      stratum[i] = AxesOf(g, units[i]).ih;
      weight[i] = units[i].weight;
    }
    Selection s = SelectStratified(stratum, weight, b.count, options.seed, kAllocationPower);
    kept = std::move(s.kept);
    factor = std::move(s.factor);
  }

  // Geometry and observations of the kept samples only, in exactly sized arrays (a full MERL
  // table has 1.1 M observations: growth by doubling would hold up to twice that).
  std::size_t n_obs = 0;
  for (std::size_t k : kept) n_obs += static_cast<std::size_t>(units[k].members);
  out.cell.reserve(n_obs);
  out.value.reserve(3 * n_obs);
  out.weight.reserve(n_obs);
  out.cos_i.reserve(n_obs);
  out.cos_o.reserve(n_obs);
  out.geometry.reserve(kept.size());
  out.obs_begin.reserve(kept.size() + 1);
  out.obs_begin.push_back(0);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const Unit& u = units[kept[k]];
    // Same operations as FromHalfDiff(CellCentre(ih, id, ip), phi_h = 0), from the tables
    // (bit-identical; tested).
    const UnitAxes a = AxesOf(g, u);
    const Vec3 d{sd[a.id] * cp[a.ip], sd[a.id] * sp[a.ip], cd[a.id]};
    const Vec3 wi{ch[a.ih] * d.x + sh[a.ih] * d.z, d.y, -sh[a.ih] * d.x + ch[a.ih] * d.z};
    const Vec3 h{sh[a.ih], 0.0, ch[a.ih]};
    const Vec3 wo = 2.0 * Dot(wi, h) * h - wi;
    const Geometry geo = MakeGeometry(wi, wo);
    out.geometry.push_back(geo);
    const double w_cell =
        options.weighting == Weighting::kBinMeasure ? CellMeasure(g, a.ih, a.id, 0) : 1.0;
    for (int m = 0; m < u.members; ++m) {
      const std::uint32_t idx = u.cells[m];
      int ih, id, ip;
      g.Unindex(idx, &ih, &id, &ip);
      const bool is_mirror = ip != a.ip;
      out.cell.push_back(idx);
      const double* v = table.Value(idx);
      out.value.insert(out.value.end(), v, v + 3);
      if (v[0] < 0 || v[1] < 0 || v[2] < 0) ++out.counts.negative;
      const double w = w_cell * factor[k];
      out.weight.push_back(w);
      out.total_weight += w;
      out.cos_i.push_back(is_mirror ? geo.cos_o : geo.cos_i);
      out.cos_o.push_back(is_mirror ? geo.cos_i : geo.cos_o);
    }
    out.obs_begin.push_back(static_cast<std::uint32_t>(out.cell.size()));
  }
  out.counts.selected = out.cell.size();
  return out;
}

Samples Subsample(const Samples& samples, std::size_t n, std::uint64_t seed) {
  const std::size_t ns = samples.NumSamples();
  std::vector<int> stratum(ns);
  std::vector<double> weight(ns, 0.0);
  for (std::size_t s = 0; s < ns; ++s) {
    int ih, id, ip;
    samples.grid.Unindex(samples.cell[samples.obs_begin[s]], &ih, &id, &ip);
    stratum[s] = ih;
    for (std::uint32_t o = samples.obs_begin[s]; o < samples.obs_begin[s + 1]; ++o) {
      weight[s] += samples.weight[o];
    }
  }
  const Selection sel = SelectStratified(stratum, weight, n, seed, kAllocationPower);
  Samples out;
  out.grid = samples.grid;
  out.options = samples.options;
  out.counts = samples.counts;
  out.obs_begin.push_back(0);
  for (std::size_t k = 0; k < sel.kept.size(); ++k) {
    const std::size_t s = sel.kept[k];
    out.geometry.push_back(samples.geometry[s]);
    for (std::uint32_t o = samples.obs_begin[s]; o < samples.obs_begin[s + 1]; ++o) {
      out.cell.push_back(samples.cell[o]);
      out.value.insert(out.value.end(), &samples.value[3 * o], &samples.value[3 * o] + 3);
      const double w = samples.weight[o] * sel.factor[k];
      out.weight.push_back(w);
      out.total_weight += w;
      out.cos_i.push_back(samples.cos_i[o]);
      out.cos_o.push_back(samples.cos_o[o]);
    }
    out.obs_begin.push_back(static_cast<std::uint32_t>(out.cell.size()));
  }
  out.counts.selected = out.cell.size();
  return out;
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
