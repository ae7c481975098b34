// Sample preparation: bin measure against analytic integrals, geometry, mirror pairing,
// cut-off, counts and budgets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "fit/bin_measure.h"
#include "fit/samples.h"
#include "fit/stratified.h"
#include "fit_test_util.h"
#include "core/error.h"
#include "models/registry.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SmallGrid;
using testing::SynthModel;

// A table with every cell valid (also below the horizon: the sampler must apply the geometry
// itself) and a value that identifies the cell.
Table AllValidTable(const Grid& g) {
  Table t = Table::Empty(g);
  for (std::size_t i = 0; i < g.NumCells(); ++i) {
    t.valid[i] = 1;
    t.Value(i)[0] = static_cast<double>(i);
    t.Value(i)[1] = 1.0;
    t.Value(i)[2] = 2.0;
  }
  return t;
}

TEST(BinMeasure, TotalsMatchAnalyticIntegrals) {
  // Over all cells: 2 pi * 4 * int_0^{pi/2} sin th dth * int_0^{pi/2} cos td sin td dtd * pi
  // = 8 pi * 1 * 1/2 * pi = 4 pi^2, for either theta_h mapping.
  for (const Grid g : {Grid::Merl(), Grid{30, 30, 60, ThetaHMapping::kLinear}}) {
    double total = 0, above = 0, cos_cos = 0;
    for (std::size_t idx = 0; idx < g.NumCells(); ++idx) {
      int ih, id, ip;
      g.Unindex(idx, &ih, &id, &ip);
      const double w = CellMeasure(g, ih, id, ip);
      total += w;
      if (g.CellAboveHorizon(idx)) {
        above += w;
        Vec3 wi, wo;
        FromHalfDiff(g.CellCentre(idx), 0.0, &wi, &wo);
        cos_cos += w * wi.z * wo.z;
      }
    }
    EXPECT_NEAR(total / (4 * kPi * kPi), 1.0, 1e-12);
    if (g == Grid::Merl()) {
      // Pairs of directions above the horizon: (2 pi)^2 ordered, each unordered pair once in
      // the folded table -> 2 pi^2; with cos_i cos_o: pi^2 / 2. Cells straddling the horizon
      // are counted whole or not at all: a sub-percent discretization error on 1-degree bins.
      EXPECT_NEAR(above / (2 * kPi * kPi), 1.0, 5e-3);
      EXPECT_NEAR(cos_cos / (kPi * kPi / 2), 1.0, 2e-3);
    }
  }
}

TEST(BinMeasure, AgreesWithMidpointRuleOfReference) {
  // Midpoint rule (fit/bin_measure.h): w = 2 pi 4 cos td sin th dth sin td dtd dphi at the centre.
  const Grid g = Grid::Merl();
  for (int ih : {10, 45, 89}) {
    for (int id : {5, 45, 80}) {
      const double th = g.ThetaHAt(ih + 0.5), td = g.ThetaDAt(id + 0.5);
      const double dth = g.ThetaHAt(ih + 1.0) - g.ThetaHAt(ih), dtd = kPi / 2 / g.n_theta_d;
      const double mid =
          2 * kPi * 4 * std::cos(td) * std::sin(th) * dth * std::sin(td) * dtd * (kPi / g.n_phi_d);
      // Second order in the bin width: 0.2 % at theta_h bin 10, where the bin is 20 % of theta_h.
      EXPECT_NEAR(CellMeasure(g, ih, id, 0) / mid, 1.0, 3e-3) << ih << " " << id;
    }
  }
}

TEST(Samples, GeometryIsBitIdenticalToMakeGeometryAtCellCentres) {
  const Grid g = Grid::Merl();
  const Table t = AllValidTable(g);
  SampleOptions o;
  o.budget = Budget::Parse("random:5000");
  const Samples s = PrepareSamples(t, o);
  ASSERT_GT(s.NumSamples(), 4000u);
  for (std::size_t k = 0; k < s.NumSamples(); ++k) {
    const Geometry ref = MakeGeometry(g.CellCentre(s.cell[s.obs_begin[k]]), 0.0);
    ASSERT_EQ(std::memcmp(&ref, &s.geometry[k], sizeof(Geometry)), 0) << "sample " << k;
  }
}

TEST(Samples, MirrorCellSwapsThetaIAndThetaOAndKeepsModelValue) {
  const Grid g = Grid::Merl();
  const Table t = AllValidTable(g);
  SampleOptions o;
  o.budget = Budget::Parse("random:3000");
  const Samples s = PrepareSamples(t, o);
  const ModelInfo* m = FindModel("lambert+ggx");
  const std::vector<double> p = Params("lambert+ggx", {"ggx.alpha=0.05"});
  int pairs = 0;
  for (std::size_t k = 0; k < s.NumSamples(); ++k) {
    for (std::uint32_t ob = s.obs_begin[k]; ob < s.obs_begin[k + 1]; ++ob) {
      const Geometry own = MakeGeometry(g.CellCentre(s.cell[ob]), 0.0);
      EXPECT_NEAR(own.cos_i, s.cos_i[ob], 1e-12);
      // The observation's cos theta_o: its sample's, swapped for the mirror cell.
      int ih, id, ip;
      g.Unindex(s.cell[ob], &ih, &id, &ip);
      const bool mirror = ip >= g.n_phi_d / 2;  // the second half of phi_d (n_phi_d even)
      EXPECT_NEAR(own.cos_o, mirror ? s.geometry[k].cos_i : s.geometry[k].cos_o, 1e-12);
      double a[3], b[3];
      m->eval(p.data(), own, a);
      m->eval(p.data(), s.geometry[k], b);
      EXPECT_NEAR(a[0] / b[0], 1.0, 1e-9);
    }
    pairs += (s.obs_begin[k + 1] - s.obs_begin[k]) == 2;
  }
  EXPECT_GT(pairs, 2000);
}

TEST(Samples, CountsCutoffAndMaskedCells) {
  const Grid g = SmallGrid();
  Table t = SynthModel("lambert", Params("lambert", {}), g);
  // Mask a few valid cells and poison a few others with NaN.
  std::size_t masked = 0, poisoned = 0;
  for (std::size_t i = 0; i < g.NumCells(); i += 7) {
    if (!t.valid[i]) continue;
    if (i % 2) {
      t.valid[i] = 0;
      ++masked;
    } else {
      t.Value(i)[1] = std::nan("");
      ++poisoned;
    }
  }
  SampleOptions o;
  o.cutoff_deg = 70;
  const Samples s = PrepareSamples(t, o);
  EXPECT_EQ(s.counts.valid, t.CountValid());
  EXPECT_EQ(s.counts.nonfinite, poisoned);
  EXPECT_EQ(s.counts.valid, s.counts.nonfinite + s.counts.beyond_cutoff + s.counts.eligible);
  EXPECT_EQ(s.counts.selected, s.counts.eligible);
  EXPECT_EQ(s.NumObservations(), s.counts.selected);
  const double cut = std::cos(70 * kPi / 180);
  for (std::size_t ob = 0; ob < s.NumObservations(); ++ob) {
    EXPECT_TRUE(t.valid[s.cell[ob]]);
    EXPECT_TRUE(std::isfinite(s.value[3 * ob + 1]));
    EXPECT_GE(s.cos_i[ob], cut - 1e-12);
  }
  // theta_o inside the cut-off too: every sample's geometry (its cells have theta_i and theta_o
  // of the sample, one way round or the other).
  for (std::size_t k = 0; k < s.NumSamples(); ++k) {
    EXPECT_GE(s.geometry[k].cos_o, cut - 1e-12);
    EXPECT_GE(s.geometry[k].cos_i, cut - 1e-12);
  }
  EXPECT_GT(masked, 0u);
}

TEST(Samples, PairingChangesEvaluationsNotObservations) {
  const Grid g = SmallGrid();
  const Table t = SynthModel("lambert", Params("lambert", {}), g, 0.0, 0.3);
  SampleOptions paired, single;
  single.pair_mirrors = false;
  const Samples a = PrepareSamples(t, paired), b = PrepareSamples(t, single);
  std::vector<std::uint32_t> ca = a.cell, cb = b.cell;
  std::sort(ca.begin(), ca.end());
  std::sort(cb.begin(), cb.end());
  EXPECT_EQ(ca, cb);
  EXPECT_NEAR(a.total_weight / b.total_weight, 1.0, 1e-12);
  EXPECT_EQ(b.NumSamples(), b.NumObservations());
  // 30 % holes: a pair keeps both cells with probability 0.49, one with 0.42, so samples are
  // 0.91 / 2 of the pairs against 0.7 of the cells: a ratio of 0.65.
  EXPECT_NEAR(static_cast<double>(a.NumSamples()) / b.NumSamples(), 0.65, 0.02);
}

TEST(Samples, StrideBudgetKeepsEveryRowsWeight) {
  const Grid g = Grid{40, 40, 90, ThetaHMapping::kSqrt};
  const Table t = SynthModel("lambert", Params("lambert", {}), g);
  SampleOptions full, stride;
  stride.budget = Budget::Parse("stride:5");
  const Samples a = PrepareSamples(t, full), b = PrepareSamples(t, stride);
  std::map<std::pair<int, int>, double> wa, wb;
  for (const auto* s : {&a, &b}) {
    auto& w = s == &a ? wa : wb;
    for (std::size_t ob = 0; ob < s->NumObservations(); ++ob) {
      int ih, id, ip;
      g.Unindex(s->cell[ob], &ih, &id, &ip);
      w[{ih, id}] += s->weight[ob];
    }
  }
  int rows = 0;
  for (const auto& [row, w] : wb) {
    EXPECT_NEAR(w / wa[row], 1.0, 1e-12);
    ++rows;
  }
  EXPECT_GT(rows, 0.9 * wa.size());
  const double fraction = static_cast<double>(b.NumObservations()) / a.NumObservations();
  EXPECT_NEAR(fraction, 0.2, 0.03);
}

TEST(Samples, RandomBudgetIsDeterministicAndKeepsStratumWeights) {
  const Grid g = Grid::Merl();
  const Table t = AllValidTable(g);
  SampleOptions o;
  o.budget = Budget::Parse("random:4000");
  const Samples a = PrepareSamples(t, o), b = PrepareSamples(t, o);
  EXPECT_EQ(a.cell, b.cell);
  EXPECT_EQ(a.weight, b.weight);
  EXPECT_NEAR(static_cast<double>(a.NumSamples()), 4000.0, 200.0);
  o.seed = 2;
  const Samples c = PrepareSamples(t, o);
  EXPECT_NE(a.cell, c.cell);
  // Each theta_h stratum keeps its total weight.
  o.budget = Budget{};
  const Samples full = PrepareSamples(t, o);
  std::map<int, double> wf, wa;
  for (const auto* s : {&full, &a}) {
    auto& w = s == &full ? wf : wa;
    for (std::size_t ob = 0; ob < s->NumObservations(); ++ob) {
      int ih, id, ip;
      g.Unindex(s->cell[ob], &ih, &id, &ip);
      w[ih] += s->weight[ob];
    }
  }
  ASSERT_EQ(wf.size(), wa.size());
  for (const auto& [ih, w] : wf) EXPECT_NEAR(wa[ih] / w, 1.0, 1e-12) << ih;
  // Every theta_h bin inside the cut-off is represented, the highlight's tiny ones included.
  EXPECT_GT(wa.size(), 80u);
}

TEST(Samples, SubsampleKeepsTotalWeight) {
  const Table t = SynthModel("lambert", Params("lambert", {}), Grid::Merl());
  const Samples full = PrepareSamples(t, SampleOptions{});
  const Samples sub = Subsample(full, 2048, 1);
  EXPECT_NEAR(sub.total_weight / full.total_weight, 1.0, 1e-12);
  EXPECT_LE(sub.NumSamples(), 2048u + 2 * 90);
  const Samples same = Subsample(sub, 1u << 30, 1);
  EXPECT_EQ(same.cell, sub.cell);
}

// What a budget must keep, computed here from the full set's cells (the oracle): stride:K keeps
// the samples whose first-half phi_d bin ip has ip % K' == K' / 2 (K' = K capped at the half
// row), each (theta_h, theta_d) row's weights scaled to keep the row's total; random:N is
// SelectStratified over (theta_h bin, sample weight) (fit/stratified.h, tested on its own).
struct ExpectedSelection {
  std::vector<std::size_t> kept;
  std::vector<double> factor;
};
ExpectedSelection Expected(const Samples& full, const Budget& b, std::uint64_t seed) {
  const Grid& g = full.grid;
  struct Key {
    int ih, id, ip;
  };
  std::vector<Key> key;
  std::vector<double> weight;
  for (std::size_t s = 0; s < full.NumSamples(); ++s) {
    Key k;
    g.Unindex(full.cell[full.obs_begin[s]], &k.ih, &k.id, &k.ip);
    if (full.options.pair_mirrors) k.ip = std::min(k.ip, g.n_phi_d - 1 - k.ip);
    key.push_back(k);
    double w = 0;
    for (std::uint32_t o = full.obs_begin[s]; o < full.obs_begin[s + 1]; ++o) w += full.weight[o];
    weight.push_back(w);
  }
  ExpectedSelection e;
  if (b.kind == Budget::Kind::kRandom) {
    std::vector<int> stratum;
    for (const Key& k : key) stratum.push_back(k.ih);
    // 0.5: the allocation power of random budgets (fit/samples.cc kAllocationPower).
    Selection sel = SelectStratified(stratum, weight, b.count, seed, 0.5);
    e.kept = sel.kept;
    e.factor = sel.factor;
    return e;
  }
  const int K = std::min(b.stride, (g.n_phi_d + 1) / 2);
  for (std::size_t begin = 0; begin < key.size();) {
    std::size_t end = begin;
    double all = 0, sel = 0;
    for (; end < key.size() && key[end].ih == key[begin].ih && key[end].id == key[begin].id; ++end) {
      all += weight[end];
      if (key[end].ip % K == K / 2) sel += weight[end];
    }
    for (std::size_t s = begin; s < end; ++s) {
      if (key[s].ip % K == K / 2) {
        e.kept.push_back(s);
        e.factor.push_back(all / sel);
      }
    }
    begin = end;
  }
  return e;
}

// SelectBudget keeps what the budget's rule says, sample for sample and bit for bit, whether
// the full set stores its geometry or computes it on demand (the fitter's metric set); and
// PrepareSamples of the budget is the same set. The table has holes, cells whose mirror alone
// is valid, negative values and odd / even phi_d counts.
TEST(Samples, SelectBudgetKeepsWhatTheBudgetsRuleSays) {
  for (const Grid g : {Grid::Merl(), Grid{30, 20, 61, ThetaHMapping::kLinear}}) {
    Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {}), g);
    for (std::size_t i = 0; i < g.NumCells(); i += 7) t.valid[i] = 0;
    for (std::size_t i = 3; i < g.NumCells(); i += 101) t.Value(i)[1] = -0.01;
    for (const bool pair : {true, false}) {
      SampleOptions full;
      full.pair_mirrors = pair;
      full.seed = 9;
      const Samples stored = PrepareSamples(t, full);
      const Samples lazy = PrepareSamples(t, full, GeometryStorage::kOnDemand);
      for (const char* text : {"stride:1", "stride:2", "stride:5", "stride:32", "stride:500",
                               "random:3000", "random:100000000"}) {
        SCOPED_TRACE(std::string(text) + (pair ? " paired" : " unpaired"));
        const Budget b = Budget::Parse(text);
        const ExpectedSelection want = Expected(stored, b, full.seed);
        ASSERT_FALSE(want.kept.empty());
        for (const Samples* from : {&stored, &lazy}) {
          const Samples got = SelectBudget(*from, b, full.seed);
          ASSERT_EQ(got.NumSamples(), want.kept.size());
          std::size_t negative = 0;
          double total = 0;
          for (std::size_t k = 0; k < want.kept.size(); ++k) {
            const std::size_t s = want.kept[k];
            ASSERT_EQ(std::memcmp(&got.geometry[k], &stored.geometry[s], sizeof(Geometry)), 0);
            ASSERT_EQ(got.obs_begin[k + 1] - got.obs_begin[k],
                      stored.obs_begin[s + 1] - stored.obs_begin[s]);
            for (std::uint32_t o = got.obs_begin[k], f = stored.obs_begin[s];
                 o < got.obs_begin[k + 1]; ++o, ++f) {
              ASSERT_EQ(got.cell[o], stored.cell[f]);
              ASSERT_EQ(std::memcmp(got.Value(o), stored.Value(f), 3 * sizeof(double)), 0);
              ASSERT_EQ(got.cos_i[o], stored.cos_i[f]);
              ASSERT_EQ(got.weight[o], stored.weight[f] * want.factor[k]);
              total += got.weight[o];
              const double* v = stored.Value(f);
              negative += v[0] < 0 || v[1] < 0 || v[2] < 0;
            }
          }
          EXPECT_EQ(got.total_weight, total);
          EXPECT_EQ(got.counts.negative, negative);
          EXPECT_EQ(got.counts.selected, got.NumObservations());
          EXPECT_EQ(got.counts.valid, stored.counts.valid);
          EXPECT_EQ(got.counts.eligible, stored.counts.eligible);
          EXPECT_TRUE(got.options.budget == b);
        }
        SampleOptions sub = full;
        sub.budget = b;
        const Samples direct = PrepareSamples(t, sub);
        const Samples selected = SelectBudget(stored, b, full.seed);
        EXPECT_EQ(direct.cell, selected.cell);
        EXPECT_EQ(direct.weight, selected.weight);
        EXPECT_TRUE(direct.counts == selected.counts);
        EXPECT_TRUE(direct.options == sub);
      }
    }
  }
}

// Geometry computed on demand (metric sets) is the stored one, bit for bit, sample for sample.
TEST(Samples, OnDemandGeometryEqualsStored) {
  for (const Grid g : {Grid::Merl(), Grid{30, 20, 61, ThetaHMapping::kLinear}}) {
    Table t = SynthModel("lambert", Params("lambert", {}), g);
    for (std::size_t i = 0; i < g.NumCells(); i += 5) t.valid[i] = 0;
    for (const bool pair : {true, false}) {
      SampleOptions o;
      o.pair_mirrors = pair;
      const Samples stored = PrepareSamples(t, o);
      const Samples lazy = PrepareSamples(t, o, GeometryStorage::kOnDemand);
      EXPECT_TRUE(lazy.geometry.empty());
      ASSERT_EQ(lazy.NumSamples(), stored.NumSamples());
      EXPECT_EQ(lazy.cell, stored.cell);
      EXPECT_EQ(lazy.weight, stored.weight);
      for (std::size_t s = 0; s < stored.NumSamples(); ++s) {
        const Geometry a = SampleGeometry(lazy, s);
        ASSERT_EQ(std::memcmp(&a, &stored.geometry[s], sizeof(Geometry)), 0) << s;
      }
    }
  }
}

// The metric set built consuming the table (values moved, not copied) holds the same
// observations as PrepareSamples of the full budget, and the table is left empty.
TEST(Samples, MetricSamplesEqualFullPreparation) {
  Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {}), Grid::Merl(), 0.05, 0.1, 3);
  SampleOptions o;
  o.budget = Budget::Parse("stride:32");  // ignored: the metric set is every cell
  SampleOptions full = o;
  full.budget = Budget{};
  const Samples direct = PrepareSamples(t, full);
  Table consumed = t;
  const Samples metric = PrepareMetricSamples(std::move(consumed), o);
  EXPECT_TRUE(consumed.rgb.empty());
  EXPECT_TRUE(metric.value.empty());
  EXPECT_TRUE(metric.geometry.empty());
  ASSERT_EQ(metric.NumObservations(), direct.NumObservations());
  EXPECT_EQ(metric.cell, direct.cell);
  EXPECT_EQ(metric.weight, direct.weight);
  EXPECT_EQ(metric.cos_i, direct.cos_i);
  EXPECT_TRUE(metric.counts == direct.counts);
  for (std::size_t ob = 0; ob < direct.NumObservations(); ++ob) {
    ASSERT_EQ(std::memcmp(metric.Value(ob), &direct.value[3 * ob], 3 * sizeof(double)), 0) << ob;
  }
}

// A stride beyond the grid's phi_d half row keeps one bin pair per row (the default stride:32
// on a small grid), not none.
TEST(Samples, LargeStrideKeepsOneBinPerRow) {
  const Grid g{20, 20, 16, ThetaHMapping::kLinear};
  const Table t = SynthModel("lambert", Params("lambert", {}), g);
  SampleOptions o;
  o.budget = Budget::Parse("stride:32");
  const Samples s = PrepareSamples(t, o);
  ASSERT_GT(s.NumSamples(), 0u);
  // Per (theta_h, theta_d) row: samples kept and their weight, against the full set's.
  auto rows = [&](const Samples& x) {
    std::map<int, std::pair<int, double>> out;
    for (std::size_t k = 0; k < x.NumSamples(); ++k) {
      int ih, id, ip;
      g.Unindex(x.cell[x.obs_begin[k]], &ih, &id, &ip);
      auto& r = out[ih * g.n_theta_d + id];
      ++r.first;
      for (std::uint32_t o = x.obs_begin[k]; o < x.obs_begin[k + 1]; ++o) r.second += x.weight[o];
    }
    return out;
  };
  const auto kept = rows(s), all = rows(PrepareSamples(t, SampleOptions{}));
  EXPECT_GT(kept.size(), all.size() / 2);
  for (const auto& [row, r] : kept) {
    EXPECT_EQ(r.first, 1) << row;
    EXPECT_NEAR(r.second / all.at(row).second, 1.0, 1e-12) << row;  // the row keeps its weight
  }
}

TEST(Budget, ParsesAndRejects) {
  EXPECT_EQ(Budget::Parse("full").kind, Budget::Kind::kFull);
  EXPECT_EQ(Budget::Parse("stride:8").stride, 8);
  EXPECT_EQ(Budget::Parse("random:4000").count, 4000u);
  EXPECT_EQ(Budget::Parse("random:4000").ToString(), "random:4000");
  for (const char* bad :
       {"", "half", "stride:0", "stride:-2", "random:", "random:1e3", "stride:4x", "random:0"}) {
    EXPECT_THROW(Budget::Parse(bad), InputError) << bad;
  }
}

TEST(Samples, RejectsBadCutoff) {
  const Table t = Table::Empty(SmallGrid());
  SampleOptions o;
  for (double c : {0.0, -5.0, 91.0, std::nan("")}) {
    o.cutoff_deg = c;
    EXPECT_THROW(PrepareSamples(t, o), InputError) << c;
  }
}

}  // namespace
}  // namespace brdfit
