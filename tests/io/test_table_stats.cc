// What `brdfit info` computes (core/table_stats.h): counts, medians, and the directional albedo
// against closed forms and an independent quadrature of the model itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/synth.h"
#include "core/table_stats.h"
#include "models/registry.h"

namespace brdfit {
namespace {

Table ModelTable(const std::string& name, const std::vector<std::string>& names,
                 const std::vector<double>& values, const Grid& g, const SynthOptions& opt = {}) {
  const ModelInfo* m = FindModel(name);
  EXPECT_NE(m, nullptr);
  std::vector<double> p = m->DefaultParams();
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto it = std::find(m->param_names.begin(), m->param_names.end(), names[k]);
    EXPECT_NE(it, m->param_names.end()) << names[k];
    p[it - m->param_names.begin()] = values[k];
  }
  return SynthesizeTable(
      g, [&](const Geometry& geo, double rgb[3]) { m->eval(p.data(), geo, rgb); }, opt);
}

// Independent estimate, straight from the model (no table): integral over wo of f cos(theta_o)
// with a midpoint rule in (u = sin^2 theta_o, phi_o), where cos(theta_o) dwo = du dphi / 2.
double ModelAlbedo(const ModelInfo& m, const std::vector<double>& p, double theta_i, int c) {
  const int nu = 1500, nphi = 1500;
  const Vec3 wi = FromSpherical(theta_i, 0.0);
  double sum = 0;
  for (int iu = 0; iu < nu; ++iu) {
    const double u = (iu + 0.5) / nu;
    const double theta_o = std::asin(std::sqrt(u));
    for (int ip = 0; ip < nphi; ++ip) {
      const Vec3 wo = FromSpherical(theta_o, (ip + 0.5) * 2 * kPi / nphi);
      double rgb[3];
      m.eval(p.data(), MakeGeometry(wi, wo), rgb);
      sum += rgb[c];
    }
  }
  return sum * 0.5 * (1.0 / nu) * (2 * kPi / nphi);
}

TEST(TableStats, LambertAlbedoIsItsDiffuseAlbedo) {
  const Table t =
      ModelTable("lambert", {"kd_r", "kd_g", "kd_b"}, {0.8, 0.5, 0.2}, Grid{45, 45, 90});
  const TableStats s = ComputeTableStats(t);
  ASSERT_EQ(s.albedo.size(), 4u);
  for (const AlbedoEstimate& a : s.albedo) {
    EXPECT_NEAR(a.coverage, 1.0, 1e-6) << a.theta_i;
    EXPECT_NEAR(a.albedo[0], 0.8, 1e-4) << a.theta_i;
    EXPECT_NEAR(a.albedo[1], 0.5, 1e-4) << a.theta_i;
    EXPECT_NEAR(a.albedo[2], 0.2, 1e-4) << a.theta_i;
  }
}

TEST(TableStats, GgxAlbedoFromTheMerlGridMatchesTheModel) {
  const ModelInfo& m = *FindModel("ggx");
  const std::vector<std::string> names = {"ks_r", "ks_g", "ks_b", "alpha"};
  for (const double alpha : {0.05, 0.3}) {
    const std::vector<double> p = {1.0, 1.0, 1.0, alpha};
    const Table t = ModelTable("ggx", names, p, Grid::Merl());
    for (const double deg : {0.0, 60.0}) {
      const double want = ModelAlbedo(m, p, deg * kPi / 180, 0);
      const AlbedoEstimate a = EstimateAlbedo(t, deg * kPi / 180);
      // Tabulation at cell centres + trilinear interpolation: ~1 % for these lobes.
      EXPECT_NEAR(a.albedo[0], want, 0.015 * want) << "alpha " << alpha << " at " << deg;
      EXPECT_GT(a.coverage, 0.999);
    }
  }
}

// Masking every cell with theta_d >= 45 deg (bins 45..89): trilinear lookups still find the
// valid bin-44 centre (44.5 deg) up to the next centre, so the covered directions are those with
// theta_d < 45.5 deg, i.e. wi . wo > cos 91 deg (cos 2 theta_d = wi . wo). The reported coverage
// is the projected measure of those directions.
TEST(TableStats, CoverageIsTheProjectedShareOfTheValidDirections) {
  Table t = ModelTable("lambert", {}, {}, Grid{45, 90, 90, ThetaHMapping::kLinear});
  for (std::size_t i = 0; i < t.valid.size(); ++i) {
    int ih, id, ip;
    t.grid.Unindex(i, &ih, &id, &ip);
    if (id >= 45) t.valid[i] = 0;
  }
  for (const double deg : {30.0, 60.0, 75.0}) {
    const Vec3 wi = FromSpherical(deg * kPi / 180, 0);
    double inside = 0, all = 0;  // midpoint rule in (sin^2 theta_o, phi_o): equal weights
    for (int iu = 0; iu < 800; ++iu) {
      for (int ip = 0; ip < 800; ++ip) {
        const Vec3 wo =
            FromSpherical(std::asin(std::sqrt((iu + 0.5) / 800)), (ip + 0.5) * kPi / 400);
        inside += Dot(wi, wo) > std::cos(91.0 * kPi / 180);
        all += 1;
      }
    }
    const AlbedoEstimate a = EstimateAlbedo(t, deg * kPi / 180);
    EXPECT_NEAR(a.coverage, inside / all, 0.002) << deg;
    EXPECT_NEAR(a.albedo[0], 0.5 * a.coverage, 1e-4) << deg;  // kd = 0.5 over what is covered
  }
  Table empty = Table::Empty(t.grid);
  const AlbedoEstimate a = EstimateAlbedo(empty, 0.3);
  EXPECT_EQ(a.coverage, 0);
  EXPECT_EQ(a.albedo[0], 0);
}

// Brute force: counts by definition, medians by full sort.
void ExpectStatsMatchBruteForce(const Table& t) {
  const Grid& g = t.grid;
  const TableStats s = ComputeTableStats(t, {});
  std::size_t below = 0, holes = 0, valid_below = 0;
  std::array<std::vector<double>, 3> v;
  for (std::size_t i = 0; i < g.NumCells(); ++i) {
    const bool above = g.CellAboveHorizon(i);
    below += !above;
    holes += above && !t.valid[i];
    valid_below += !above && t.valid[i];
    if (t.valid[i]) {
      for (int c = 0; c < 3; ++c) v[c].push_back(t.Value(i)[c]);
    }
  }
  EXPECT_EQ(s.cells, g.NumCells());
  EXPECT_EQ(s.valid, t.CountValid());
  EXPECT_EQ(s.below_horizon, below);
  EXPECT_EQ(s.masked_above_horizon, holes);
  EXPECT_EQ(s.valid_below_horizon, valid_below);
  for (int c = 0; c < 3; ++c) {
    std::sort(v[c].begin(), v[c].end());
    const std::size_t n = v[c].size();
    const double median = n % 2 ? v[c][n / 2] : 0.5 * (v[c][n / 2 - 1] + v[c][n / 2]);
    EXPECT_EQ(s.channels[c].min, v[c].front());
    EXPECT_EQ(s.channels[c].max, v[c].back());
    EXPECT_EQ(s.channels[c].median, median) << n;
  }
  const auto j = TableStatsToJson(s);
  EXPECT_EQ(j["valid"], s.valid);
  EXPECT_EQ(j["channels_1_per_sr"]["G"]["median"], s.channels[1].median);
}

TEST(TableStats, CountsAndChannelSummaries) {
  const Grid g{10, 10, 20, ThetaHMapping::kSqrt};
  Table t = ModelTable("lambert+ggx", {}, {}, g, {0.1, 0.25, 5});
  const std::size_t last = g.NumCells() - 1;  // theta_h, theta_d near 90 deg: below the horizon
  ASSERT_FALSE(g.CellAboveHorizon(last));
  t.valid[last] = 1;
  ExpectStatsMatchBruteForce(t);
  t.valid[last - 1] = !t.valid[last - 1];  // the other parity of the valid count
  ExpectStatsMatchBruteForce(t);
  EXPECT_EQ(ComputeTableStats(t, {}).valid_below_horizon, 1u + !g.CellAboveHorizon(last - 1));
}

// The medians are selected by the values' bit patterns (radix selection): any finite values
// must give the full sort's medians, including negatives, zeros of both signs, subnormals,
// values many orders of magnitude apart, long runs of one value and the two middle ranks
// falling in different or equal buckets. 16000 cells, so that a bucket holding most of them
// (the runs of few values, the duplicates) is narrowed by the lower digits too.
TEST(TableStats, MediansOfAnyFiniteValuesMatchAFullSort) {
  const Grid g{20, 20, 40, ThetaHMapping::kSqrt};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const std::vector<double> special = {0.0,    -0.0, 5e-324, -5e-324, 1.0,
                                       1.0625, -1.0, 1e300,  -1e300,  2.2250738585072014e-308};
  for (int trial = 0; trial < 16; ++trial) {
    Table t = Table::Empty(g);
    for (std::size_t i = 0; i < g.NumCells(); ++i) {
      t.valid[i] = u(rng) < 0.9;
      for (int c = 0; c < 3; ++c) {
        const double r = u(rng);
        double v = 0;
        if (trial % 4 == 0) {
          v = special[static_cast<std::size_t>(u(rng) * special.size())];  // runs of few values
        } else if (trial % 4 == 1) {
          v = (r < 0.3 ? -1 : 1) * std::pow(10.0, -300 + 600 * u(rng));  // every magnitude
        } else if (trial % 4 == 2) {
          v = 0.5 + 1e-9 * std::floor(8 * u(rng));  // one bucket, many duplicates
        } else {
          v = 0.5 * (1 + 1e-6 * u(rng));  // one bucket down to the lowest digits, distinct
        }
        t.Value(i)[c] = v;
      }
    }
    SCOPED_TRACE(trial);
    ExpectStatsMatchBruteForce(t);
    t.valid[0] = !t.valid[0];  // the other parity of the valid count
    ExpectStatsMatchBruteForce(t);
  }
}

}  // namespace
}  // namespace brdfit
