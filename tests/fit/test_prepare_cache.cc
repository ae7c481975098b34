// The per-grid work of PrepareTable done once (fit/sample_plan.h, fit/prepare_cache.h,
// RenderedPlan of fit/rendered_error.h; issue 18): a plan made for one table serves every table
// of its grid with the same bits as a preparation from scratch, whatever that table's mask;
// the plans agree with the definitions they cache (cell-centre geometry, the cut-off, the
// measured lookups); the cache is shared between threads and bounded.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <set>
#include <thread>
#include <vector>

#include "core/error.h"
#include "fit/fitter.h"
#include "fit/prepare_cache.h"
#include "fit/rendered_error.h"
#include "fit/sample_plan.h"
#include "fit_test_util.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SmallGrid;
using testing::SynthModel;

template <class T>
bool SameBits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void ExpectSameSamples(const Samples& a, const Samples& b) {
  EXPECT_TRUE(a.grid == b.grid);
  EXPECT_TRUE(a.options == b.options);
  EXPECT_TRUE(a.counts == b.counts);
  EXPECT_TRUE(SameBits(a.obs_begin, b.obs_begin));
  EXPECT_TRUE(SameBits(a.cell, b.cell));
  // The values per observation (a metric set made consuming its table holds the table's array
  // instead of a copy per observation).
  ASSERT_EQ(a.NumObservations(), b.NumObservations());
  for (std::size_t o = 0; o < a.NumObservations(); ++o) {
    ASSERT_EQ(std::memcmp(a.Value(o), b.Value(o), 3 * sizeof(double)), 0) << o;
  }
  EXPECT_TRUE(SameBits(a.weight, b.weight));
  EXPECT_TRUE(SameBits(a.cos_i, b.cos_i));
  EXPECT_EQ(std::memcmp(&a.total_weight, &b.total_weight, sizeof(double)), 0);
  ASSERT_EQ(a.geometry.size(), b.geometry.size());
  for (std::size_t s = 0; s < a.geometry.size(); ++s) {
    ASSERT_EQ(std::memcmp(&a.geometry[s], &b.geometry[s], sizeof(Geometry)), 0) << s;
  }
}

void ExpectSameReference(const RenderedReference& a, const RenderedReference& b) {
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const auto &p = a.pixels[i], &q = b.pixels[i];
    ASSERT_TRUE(p.x == q.x && p.y == q.y) << i;
    ASSERT_EQ(std::memcmp(p.measured.data(), q.measured.data(), 3 * sizeof(double)), 0) << i;
    ASSERT_EQ(std::memcmp(&p.wi, &q.wi, sizeof(Vec3)), 0) << i;
    ASSERT_EQ(std::memcmp(&p.wo, &q.wo, sizeof(Vec3)), 0) << i;
  }
  ASSERT_EQ(a.masked.size(), b.masked.size());
  for (std::size_t i = 0; i < a.masked.size(); ++i) {
    EXPECT_TRUE(a.masked[i].light == b.masked[i].light && a.masked[i].x == b.masked[i].x &&
                a.masked[i].y == b.masked[i].y);
  }
  EXPECT_EQ(a.begin, b.begin);
  EXPECT_EQ(a.peak_y, b.peak_y);
  EXPECT_EQ(a.env_peak_y, b.env_peak_y);
  EXPECT_EQ(a.counts.lit_pixels, b.counts.lit_pixels);
  EXPECT_EQ(a.counts.masked_pixels, b.counts.masked_pixels);
  EXPECT_EQ(a.counts.sphere_pixels, b.counts.sphere_pixels);
}

void ExpectSamePrepared(const PreparedTable& a, const PreparedTable& b) {
  EXPECT_EQ(a.has_own_metric, b.has_own_metric);
  ExpectSameSamples(a.fit, b.fit);
  ExpectSameSamples(a.metric(), b.metric());
  EXPECT_TRUE(SameBits(a.loss.mult, b.loss.mult));
  EXPECT_TRUE(SameBits(a.loss.sqrt_w, b.loss.sqrt_w));
  EXPECT_TRUE(SameBits(a.loss.target, b.loss.target));
  EXPECT_TRUE(SameBits(a.loss.inv, b.loss.inv));
  ExpectSameReference(a.rendered, b.rendered);
  ExpectSameReference(a.rendered_check, b.rendered_check);
}

// A table of the grid with its own holes, a few non-finite and negative values and, unlike a
// measured table, valid cells below the horizon (the plan must apply the geometry itself).
Table OddTable(const Grid& g, std::uint64_t seed) {
  Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {"alpha=0.15"}), g, 0.05, 0.2, seed);
  for (std::size_t i = seed; i < g.NumCells(); i += 97) {
    if (i % 3 == 0) t.Value(i)[1] = std::nan("");
    if (i % 3 == 1) t.Value(i)[2] = -0.01;
    if (i % 3 == 2) t.valid[i] = 1;  // also below the horizon
  }
  return t;
}

// The sample plan is the definition it caches: cos theta_i of every member equals the
// cell-centre geometry's (MakeGeometry(CellCentre)), the mirror's the primary's cos theta_o,
// and its units are the cells whose directions are inside the cut-off.
TEST(SamplePlan, IsTheCellCentreGeometryInsideTheCutoff) {
  for (const Grid g : {SmallGrid(), Grid{21, 17, 45, ThetaHMapping::kLinear}}) {
    SampleOptions o;
    o.cutoff_deg = 75;
    const SamplePlan plan = MakeSamplePlan(g, o);
    EXPECT_TRUE(plan.Matches(g, o));
    const double cut = std::cos(75 * kPi / 180);
    std::set<std::uint32_t> in_plan;
    for (std::size_t u = 0; u < plan.NumUnits(); ++u) {
      const std::uint32_t first = plan.cell[plan.unit_begin[u]];
      const Geometry geo = MakeGeometry(g.CellCentre(first));
      for (std::uint32_t m = plan.unit_begin[u]; m < plan.unit_begin[u + 1]; ++m) {
        const double expected = m == plan.unit_begin[u] ? geo.cos_i : geo.cos_o;
        ASSERT_EQ(std::memcmp(&plan.cos_i[m], &expected, sizeof(double)), 0) << u;
        in_plan.insert(plan.cell[m]);
      }
    }
    for (std::size_t c = 0; c < g.NumCells(); ++c) {
      const Geometry geo = MakeGeometry(g.CellCentre(c));
      const double lo = std::min(geo.cos_i, geo.cos_o);
      if (std::abs(lo - cut) < 1e-12) continue;  // on the boundary: rounding decides
      EXPECT_EQ(in_plan.count(static_cast<std::uint32_t>(c)) == 1, lo >= cut) << c;
    }
  }
}

// A plan made while preparing one table gives every other table of the grid the same
// preparation as one from scratch, for every budget kind, weighting and pairing; the second
// table's masked cells are never among its observations.
TEST(PrepareCache, PlanOfOneTableServesAnotherBitForBit) {
  const Grid g = SmallGrid();
  const Table first = OddTable(g, 1), second = OddTable(g, 2);
  for (const char* budget : {"stride:4", "full", "random:500"}) {
    for (const bool pair : {true, false}) {
      SampleOptions so;
      so.budget = Budget::Parse(budget);
      so.pair_mirrors = pair;
      so.weighting = pair ? Weighting::kBinMeasure : Weighting::kUniform;
      FitOptions fo = LogLossUnpolished();
      fo.loss = LossKind::kRel;
      SCOPED_TRACE(std::string(budget) + (pair ? " paired" : " unpaired"));
      PrepareCache cache;
      PrepareTable(first, so, fo, &cache);
      const PreparedTable cached = PrepareTable(second, so, fo, &cache);
      ExpectSamePrepared(cached, PrepareTable(second, so, fo));
      Table consumed = second;
      ExpectSamePrepared(PrepareTable(std::move(consumed), so, fo, &cache), cached);
      // One sample plan and the rendered plans of the two lattices (fit/narrow_peak.h).
      EXPECT_EQ(cache.GetStats().made, 3u);
      for (std::uint32_t c : cached.metric().cell) ASSERT_TRUE(second.valid[c]) << c;
      EXPECT_GT(cached.metric().counts.nonfinite, 0u);
      EXPECT_GT(cached.metric().counts.negative, 0u);
    }
  }
}

// The rendered reference from the plan is the definition: each lit pixel's measured radiance is
// RenderedLookup of the table at its directions times n.l, and the masked pixels are those
// whose lookup has no valid cell.
TEST(RenderedPlan, ReferenceIsTheTablesOwnLookups) {
  const Grid g = SmallGrid();
  Table t = OddTable(g, 3);
  for (std::size_t i = 0; i < g.NumCells(); i += 2) t.valid[i] = 0;  // many masked lookups
  RenderedErrorOptions ro;
  ro.resolution = 24;
  const RenderedPlan plan = MakeRenderedPlan(g, ro);
  const RenderedReference ref = PrepareRenderedReference(t, plan);
  ASSERT_FALSE(ref.pixels.empty());
  for (const RenderedReference::Pixel& p : ref.pixels) {
    const auto m = RenderedLookup(t, p.wi, p.wo);
    ASSERT_TRUE(m.has_value());
    for (int c = 0; c < 3; ++c) ASSERT_EQ(p.measured[c], (*m)[c] * p.cos_l);
  }
  EXPECT_EQ(ref.pixels.size() + ref.masked.size(), plan.lit.size());
  std::size_t looked_up_masked = 0;
  for (const RenderedPlan::Pixel& p : plan.lit) {
    const auto m = RenderedLookup(t, p.wi, p.wo);
    looked_up_masked += !m || !(std::isfinite((*m)[0]) && std::isfinite((*m)[1]) &&
                                std::isfinite((*m)[2]));
  }
  EXPECT_EQ(looked_up_masked, ref.masked.size());
  EXPECT_GT(ref.masked.size(), 0u);
  ExpectSameReference(ref, PrepareRenderedReference(t, ro));
  EXPECT_THROW(PrepareRenderedReference(t, MakeRenderedPlan(Grid{10, 10, 20}, ro)),
               std::invalid_argument);
}

// Threads asking for one plan at once get one plan, made once; other options make another;
// at most `capacity` plans of a kind are held, and a plan a caller holds outlives its eviction.
TEST(PrepareCache, SharedBetweenThreadsAndBounded) {
  const Grid g{12, 12, 24};
  PrepareCache cache(2);
  SampleOptions o;
  std::vector<std::shared_ptr<const SamplePlan>> got(8);
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < got.size(); ++k) {
    threads.emplace_back([&, k] { got[k] = cache.Samples(g, o); });
  }
  for (auto& t : threads) t.join();
  for (const auto& p : got) EXPECT_EQ(p.get(), got[0].get());
  EXPECT_EQ(cache.GetStats().made, 1u);
  EXPECT_EQ(cache.GetStats().reused, got.size() - 1);
  // The budget and seed are applied per table: the same plan.
  SampleOptions strided = o;
  strided.budget = Budget::Parse("stride:3");
  strided.seed = 9;
  EXPECT_EQ(cache.Samples(g, strided).get(), got[0].get());
  SampleOptions other = o;
  other.cutoff_deg = 60;
  const auto p60 = cache.Samples(g, other);
  EXPECT_NE(p60.get(), got[0].get());
  EXPECT_TRUE(p60->Matches(g, other));
  other.cutoff_deg = 50;
  cache.Samples(g, other);  // the third plan: the least recently used (the 80-degree one) goes
  EXPECT_EQ(cache.GetStats().entries, 2u);
  EXPECT_EQ(cache.GetStats().made, 3u);
  EXPECT_GT(got[0]->NumUnits(), 0u);  // still valid for its holder
  EXPECT_NE(cache.Samples(g, o).get(), got[0].get());  // made again
  EXPECT_EQ(cache.GetStats().made, 4u);
  // A plan that cannot be made is an error for every request, and not kept.
  SampleOptions bad = o;
  bad.cutoff_deg = 95;
  EXPECT_THROW(cache.Samples(g, bad), InputError);
  EXPECT_THROW(cache.Samples(g, bad), InputError);
  EXPECT_EQ(cache.GetStats().entries, 2u);
  // A plan of another grid or options is refused, not misapplied.
  const Table t = OddTable(Grid{10, 10, 20}, 1);
  EXPECT_THROW(PrepareSamples(t, *got[0], o), std::invalid_argument);
  EXPECT_THROW(PrepareSamples(Table::Empty(g), *p60, o), std::invalid_argument);
}

}  // namespace
}  // namespace brdfit
