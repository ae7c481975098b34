// Metrics against an independent brute-force computation over the table's cells, and their
// basic properties.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

#include "fit/fitter.h"
#include "fit/fast_cbrt.h"
#include "fit/metrics.h"
#include "fit/vector_log1p.h"
#include "fit/samples.h"
#include "fit_test_util.h"
#include "models/registry.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SmallGrid;
using testing::SynthModel;

// Simpson's rule on [a, b] with 64 intervals.
template <class F>
double Simpson(F f, double a, double b) {
  const int n = 64;
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4 : 2);
  return s * h / 3;
}

struct Brute {
  double log_rmse, cbrt_rmse, rel_l2;
};

// Straight from the definitions (fit/metrics.h): every valid cell of the table whose centre
// directions are inside the cut-off, its own geometry (no mirror pairing), the cell measure by
// numerical integration, plain std::log1p / std::cbrt.
Brute BruteForce(const Table& t, const ModelInfo& m, const std::vector<double>& p, double cut) {
  const Grid& g = t.grid;
  double sw = 0, sl = 0, sc = 0, num = 0, den = 0;
  for (std::size_t idx = 0; idx < g.NumCells(); ++idx) {
    if (!t.valid[idx]) continue;
    Vec3 wi, wo;
    FromHalfDiff(g.CellCentre(idx), 0.0, &wi, &wo);
    if (wi.z < std::cos(cut) || wo.z < std::cos(cut)) continue;
    int ih, id, ip;
    g.Unindex(idx, &ih, &id, &ip);
    const double ih_int =
        Simpson([](double x) { return std::sin(x); }, g.ThetaHAt(ih), g.ThetaHAt(ih + 1.0));
    const double id_int = Simpson([](double x) { return std::sin(x) * std::cos(x); },
                                  g.ThetaDAt(id), g.ThetaDAt(id + 1.0));
    const double w = 2 * kPi * 4 * ih_int * id_int * kPi / g.n_phi_d;
    double f[3];
    m.eval(p.data(), MakeGeometry(wi, wo), f);
    const double c = wi.z;
    for (int ch = 0; ch < 3; ++ch) {
      const double v = t.Value(idx)[ch];
      sl += w * std::pow(std::log1p(f[ch] * c) - std::log1p(v * c), 2);
      sc += w * std::pow(std::cbrt(f[ch] * c) - std::cbrt(v * c), 2);
      num += w * c * c * (f[ch] - v) * (f[ch] - v);
      den += w * c * c * v * v;
    }
    sw += 3 * w;
  }
  return {std::sqrt(sl / sw), std::sqrt(sc / sw), std::sqrt(num / den)};
}

std::vector<double> Predict(const Samples& s, const ModelInfo& m, const std::vector<double>& p) {
  std::vector<double> per_sample(3 * s.NumSamples());
  for (std::size_t k = 0; k < s.NumSamples(); ++k)
    m.eval(p.data(), s.geometry[k], &per_sample[3 * k]);
  return ExpandToObservations(s, per_sample);
}

TEST(Metrics, MatchIndependentBruteForce) {
  const Grid g = SmallGrid();
  const std::vector<double> truth = Params("lambert+ggx", {"ggx.alpha=0.08"});
  const Table t = SynthModel("lambert+ggx", truth, g, 0.05, 0.2, 3);
  const ModelInfo& m = *FindModel("lambert+ggx");
  // A deliberately wrong model: other alpha and colours.
  const std::vector<double> p =
      Params("lambert+ggx", {"ggx.alpha=0.15", "lambert.kd_r=0.3", "ggx.ks_b=0.05"});
  SampleOptions o;
  o.cutoff_deg = 75;
  const Samples s = PrepareSamples(t, o);
  const FitMetrics fm = ComputeMetrics(s, Predict(s, m, p));
  const Brute b = BruteForce(t, m, p, 75 * kPi / 180);
  ASSERT_TRUE(fm.ok) << fm.problem;
  EXPECT_NEAR(fm.log_rmse / b.log_rmse, 1.0, 1e-9);
  EXPECT_NEAR(fm.cbrt_rmse / b.cbrt_rmse, 1.0, 1e-9);
  EXPECT_NEAR(fm.rel_l2 / b.rel_l2, 1.0, 1e-9);
  EXPECT_GT(fm.log_rmse, 0.01);
  EXPECT_EQ(fm.weighting, "bin-measure");
  EXPECT_EQ(fm.cutoff_deg, 75);
  EXPECT_EQ(fm.cells, s.NumObservations());
  // The worst cell is one of the samples, with its own values.
  EXPECT_GT(fm.worst.log_error, fm.log_rmse);
  EXPECT_TRUE(t.valid[fm.worst.cell]);
  EXPECT_EQ(fm.worst.measured[0], t.Value(fm.worst.cell)[0]);
}

TEST(Metrics, PerSamplePredictionsGiveBitIdenticalMetrics) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {}), SmallGrid(), 0.05, 0.2, 5);
  const ModelInfo& m = *FindModel("lambert+ggx");
  const std::vector<double> p = Params("lambert+ggx", {"ggx.alpha=0.2"});
  const Samples s = PrepareSamples(t, SampleOptions{});
  ASSERT_LT(s.NumSamples(), s.NumObservations());  // mirrors share samples
  std::vector<double> per_sample(3 * s.NumSamples());
  for (std::size_t k = 0; k < s.NumSamples(); ++k)
    m.eval(p.data(), s.geometry[k], &per_sample[3 * k]);
  const FitMetrics a = ComputeMetrics(s, ExpandToObservations(s, per_sample));
  const FitMetrics b = ComputeMetricsPerSample(s, per_sample);
  ASSERT_TRUE(a.ok && b.ok);
  EXPECT_EQ(a.log_rmse, b.log_rmse);
  EXPECT_EQ(a.cbrt_rmse, b.cbrt_rmse);
  EXPECT_EQ(a.rel_l2, b.rel_l2);
  EXPECT_EQ(a.worst.cell, b.worst.cell);
  EXPECT_EQ(a.worst.predicted[1], b.worst.predicted[1]);
  per_sample[4] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(ComputeMetricsPerSample(s, per_sample).ok);
  EXPECT_THROW(ComputeMetricsPerSample(s, std::vector<double>(3)), std::invalid_argument);
}

// The streamed pass (predictions made per chunk by the thread that scores it, never stored)
// gives the per-sample pass's bits, on a table with zero cells (the cube roots' guard) and for
// any thread count.
TEST(Metrics, StreamedPassGivesBitIdenticalMetrics) {
  Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {}), SmallGrid(), 0.05, 0.2, 5);
  for (std::size_t i = 0; i < t.grid.NumCells(); i += 7) t.rgb[3 * i + 1] = 0.0;  // dark cells
  const ModelInfo& m = *FindModel("lambert+ggx");
  const std::vector<double> p = Params("lambert+ggx", {"ggx.alpha=0.2"});
  const Samples s = PrepareSamples(t, SampleOptions{});
  std::vector<double> per_sample(3 * s.NumSamples());
  for (std::size_t k = 0; k < s.NumSamples(); ++k)
    m.eval(p.data(), s.geometry[k], &per_sample[3 * k]);
  const FitMetrics a = ComputeMetricsPerSample(s, per_sample);
  const SampleEvaluator eval = [&](std::size_t begin, std::size_t end, double* out) {
    for (std::size_t k = begin; k < end; ++k)
      m.eval(p.data(), s.geometry[k], out + 3 * (k - begin));
  };
  for (int threads : {1, 3}) {
    const FitMetrics b = ComputeMetricsStreamed(s, eval, threads);
    ASSERT_TRUE(a.ok && b.ok);
    EXPECT_EQ(a.log_rmse, b.log_rmse) << threads;
    EXPECT_EQ(a.cbrt_rmse, b.cbrt_rmse) << threads;
    EXPECT_EQ(a.rel_l2, b.rel_l2);
    EXPECT_EQ(a.worst.cell, b.worst.cell);
    EXPECT_EQ(a.worst.predicted, b.worst.predicted);
  }
}

TEST(Metrics, PerfectAndScaledPredictions) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {}), SmallGrid());
  const Samples s = PrepareSamples(t, SampleOptions{});
  std::vector<double> exact(s.value.begin(), s.value.end());
  FitMetrics m = ComputeMetrics(s, exact);
  EXPECT_TRUE(m.ok);
  EXPECT_EQ(m.log_rmse, 0.0);
  EXPECT_EQ(m.cbrt_rmse, 0.0);
  EXPECT_EQ(m.rel_l2, 0.0);
  for (double& v : exact) v *= 2;
  m = ComputeMetrics(s, exact);
  EXPECT_NEAR(m.rel_l2, 1.0, 1e-12);  // ||2m - m|| / ||m||
  // cbrt(2 x) - cbrt(x) = (2^(1/3) - 1) cbrt(x).
  double sum = 0;
  for (std::size_t ob = 0; ob < s.NumObservations(); ++ob) {
    for (int ch = 0; ch < 3; ++ch) {
      sum += s.weight[ob] * std::pow(std::cbrt(s.value[3 * ob + ch] * s.cos_i[ob]), 2);
    }
  }
  EXPECT_NEAR(m.cbrt_rmse / ((std::cbrt(2.0) - 1) * std::sqrt(sum / (3 * s.total_weight))), 1.0,
              1e-12);
}

TEST(Metrics, NonFinitePredictionIsReportedNotPropagated) {
  const Table t = SynthModel("lambert", Params("lambert", {}), SmallGrid());
  const Samples s = PrepareSamples(t, SampleOptions{});
  std::vector<double> pred(s.value.begin(), s.value.end());
  pred[7] = std::numeric_limits<double>::quiet_NaN();
  const FitMetrics m = ComputeMetrics(s, pred);
  EXPECT_FALSE(m.ok);
  EXPECT_FALSE(m.problem.empty());
  EXPECT_TRUE(std::isfinite(m.log_rmse) && std::isfinite(m.cbrt_rmse) && std::isfinite(m.rel_l2));
  EXPECT_THROW(ComputeMetrics(s, std::vector<double>(3)), std::invalid_argument);
}

TEST(Metrics, FitCostEqualsMetricForMatchingLoss) {
  // With the full budget the fit samples are the metric samples: the log loss's cost is
  // log_rmse^2 and the cube-root loss's cost is cbrt_rmse^2 (fit/loss.h).
  const Table t =
      SynthModel("lambert+ggx", Params("lambert+ggx", {"ggx.alpha=0.2"}), SmallGrid(), 0.1, 0.0, 5);
  for (const LossKind loss : {LossKind::kLog, LossKind::kCbrt}) {
    FitOptions fo = LogLossUnpolished();
    fo.loss = loss;
    const FitResult r = FitTable("lambert+ggx", t, SampleOptions{}, fo);
    ASSERT_FALSE(r.Failed()) << r.message;
    const double metric = loss == LossKind::kLog ? r.metrics.log_rmse : r.metrics.cbrt_rmse;
    EXPECT_NEAR(r.final_cost / (metric * metric), 1.0, 1e-9) << ToString(loss);
  }
}

// The metric pass shared by threads gives the same bits as one thread (fixed chunks summed in
// order), on a full MERL-grid set (many chunks) with a worst cell to find.
TEST(Metrics, ThreadsGiveTheSameBits) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {}), Grid::Merl(), 0.05, 0.1, 7);
  const ModelInfo& m = *FindModel("lambert+ggx");
  const std::vector<double> p = Params("lambert+ggx", {"ggx.alpha=0.3"});
  const Samples s = PrepareSamples(t, SampleOptions{}, GeometryStorage::kOnDemand);
  std::vector<double> pred(3 * s.NumSamples());
  for (std::size_t k = 0; k < s.NumSamples(); ++k) m.eval(p.data(), SampleGeometry(s, k), &pred[3 * k]);
  const FitMetrics one = ComputeMetricsPerSample(s, pred, 1);
  ASSERT_TRUE(one.ok);
  for (const int threads : {2, 3, 8}) {
    const FitMetrics many = ComputeMetricsPerSample(s, pred, threads);
    EXPECT_EQ(many.log_rmse, one.log_rmse) << threads;
    EXPECT_EQ(many.cbrt_rmse, one.cbrt_rmse) << threads;
    EXPECT_EQ(many.rel_l2, one.rel_l2) << threads;
    EXPECT_EQ(many.worst.cell, one.worst.cell) << threads;
    EXPECT_EQ(many.worst.log_error, one.worst.log_error) << threads;
  }
  // And the per-observation entry point agrees with the per-sample one.
  const FitMetrics obs = ComputeMetrics(s, ExpandToObservations(s, pred), 3);
  EXPECT_EQ(obs.log_rmse, one.log_rmse);
  EXPECT_EQ(obs.worst.cell, one.worst.cell);
}

// n values log-uniform over the range the metrics' cube roots meet (the guard 1e-5 up to
// 1e300), from a fixed 64-bit LCG seeded with `seed`: the same values on every platform.
std::vector<double> MetricRangeValues(int n, std::uint64_t seed) {
  std::vector<double> x;
  std::uint64_t state = seed;
  for (int i = 0; i < n; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    x.push_back(std::pow(10.0, -5.0 + 305.0 * static_cast<double>(state >> 11) * 0x1.0p-53));
  }
  return x;
}

// FastCbrt (the metrics' cube root) against libm's over the range the metrics meet (the guard
// 1e-5 up to 1e300), log-uniformly, and at exact cubes.
TEST(Metrics, FastCbrtMatchesLibm) {
  double worst = 0;
  for (const double x : MetricRangeValues(200000, 12345)) {
    const double ref = std::cbrt(x);
    worst = std::max(worst, std::abs(FastCbrt(x) - ref) / ref);
  }
  EXPECT_LT(worst, 4 * std::numeric_limits<double>::epsilon()) << worst;
  for (const double r : {0.05, 1.0, 2.0, 3.0, 10.0, 1e50}) {
    EXPECT_NEAR(FastCbrt(r * r * r) / r, 1.0, 4 * std::numeric_limits<double>::epsilon()) << r;
  }
}

// The metric pass's vectorized guesses are the scalar guess, bit for bit (odd lengths take the
// scalar tail), over the metrics' range and at the edges of the 32-bit division.
TEST(Metrics, FastCbrtGuessesMatchTheScalarGuess) {
  std::vector<double> x = MetricRangeValues(4097, 777);
  for (const double v : {1e-5, 1.0, 2.0, 3.0, 1e300, std::numeric_limits<double>::max(),
                         std::numeric_limits<double>::min(), 0x1.fffffffffffffp-1}) {
    x.push_back(v);
  }
  std::vector<double> y(x.size());
  FastCbrtGuesses(x.data(), x.size(), y.data());
  for (std::size_t k = 0; k < x.size(); ++k) {
    ASSERT_EQ(std::bit_cast<std::uint64_t>(y[k]), std::bit_cast<std::uint64_t>(FastCbrtGuess(x[k])))
        << x[k];
    // ~5 correct bits, what two Halley steps and a Newton step need for full precision.
    ASSERT_LT(std::abs(y[k] / std::cbrt(x[k]) - 1.0), 0.07) << x[k];
  }
}

// The metrics' array log1p against libm's, one value at a time: within 2 ulp over the range
// the log differences take (relative errors from -99.9 % to x1000, and tiny ones), NaN kept (the
// guard's marker), every tail length. On a machine without AVX2 it is libm's, bit for bit.
TEST(Metrics, ArrayLog1pMatchesLibm) {
  std::vector<double> x;
  std::uint64_t state = 99;
  for (int i = 0; i < 20000; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const double u = static_cast<double>(state >> 11) * 0x1.0p-53;
    const double mag = std::pow(10.0, -16.0 + 19.0 * u);  // 1e-16 .. 1e3
    x.push_back((i % 2 == 0 || mag > 0.999) ? mag : -mag);
  }
  x.push_back(std::numeric_limits<double>::quiet_NaN());
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{3}, std::size_t{6},
                              x.size()}) {
    std::vector<double> y(n);
    Log1pAll(x.data(), n, y.data());
    for (std::size_t k = 0; k < n; ++k) {
      const double ref = std::log1p(x[k]);
      if (std::isnan(ref)) {
        ASSERT_TRUE(std::isnan(y[k])) << k;
        continue;
      }
      const double ulp = std::abs(std::nextafter(ref, HUGE_VAL) - ref);
      ASSERT_LE(std::abs(y[k] - ref), 2 * ulp) << x[k];
      if (!Log1pAllIsVectorized()) {
        ASSERT_EQ(y[k], ref) << x[k];
      }
    }
  }
  // In place, as the metric pass calls it.
  std::vector<double> z(x.begin(), x.begin() + 7), copy = z, out(7);
  Log1pAll(copy.data(), 7, out.data());
  Log1pAll(z.data(), 7, z.data());
  EXPECT_EQ(z, out);
}

// The refinement over an array (AVX2 clone on a machine that has it, else SSE2) is the scalar
// refinement, bit for bit, for every length's tail.
TEST(Metrics, RefinedCubeRootsMatchTheScalarRefinement) {
  const std::vector<double> x = MetricRangeValues(1027, 4242);
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{3}, std::size_t{5},
                              x.size()}) {
    std::vector<double> y(n);
    FastCbrtGuesses(x.data(), n, y.data());
    FastCbrtRefineAll(x.data(), n, y.data());
    for (std::size_t k = 0; k < n; ++k) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(y[k]), std::bit_cast<std::uint64_t>(FastCbrt(x[k])))
          << n << " " << k;
    }
  }
}

}  // namespace
}  // namespace brdfit
