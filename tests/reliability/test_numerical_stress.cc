// Numerical stress suite: tables that push the fitter to its edges. Every case must end in a
// finite fit or a failure status with a message; never a NaN or Inf in a result, never an
// exception other than the documented InputError, never a hang (iterations are bounded here;
// time by CTest's per-test timeout).
//
// Cases (issue "Reliability"): alpha at its bounds, grazing-only data, retro-reflection cells,
// all-zero table, constant table, a single valid cell, dynamic range 1e-8..1e5, 50 % NaN cells
// (in an HDF5 table and in memory), 90 % missing, every cell invalid, pure noise. Each is fitted
// with several catalog models and, for the degenerate ones, every loss.
//
// The grid is a small sqrt-mapped one (16 x 16 x 32 cells, MERL's layout at 1/10 of the bins):
// the point is the data's pathologies, not its resolution.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "fit/fitter.h"
#include "fit/samples.h"
#include "fuzz/harness_util.h"
#include "core/error.h"
#include "io/hdf5_table.h"
#include "core/synth.h"
#include "models/registry.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;

Grid StressGrid() {
  Grid g;
  g.n_theta_h = 16;
  g.n_theta_d = 16;
  g.n_phi_d = 32;
  g.theta_h_mapping = ThetaHMapping::kSqrt;
  return g;
}

// A table of `model` at `params` on the stress grid (cells below the horizon masked).
Table Synth(const std::string& model, const std::vector<double>& params,
            const SynthOptions& options = {}) {
  const ModelInfo* m = FindModel(model);
  EXPECT_NE(m, nullptr) << model;
  EXPECT_EQ(params.size(), m->params.size()) << model;
  return SynthesizeTable(
      StressGrid(), [&](const Geometry& g, double rgb[3]) { m->eval(params.data(), g, rgb); },
      options);
}

// Every above-horizon cell valid with value v(idx, channel).
template <class F>
Table Filled(F value) {
  Table t = Table::Empty(StressGrid());
  for (std::size_t i = 0; i < t.grid.NumCells(); ++i) {
    if (!t.grid.CellAboveHorizon(i)) continue;
    t.valid[i] = 1;
    for (int c = 0; c < 3; ++c) t.rgb[3 * i + c] = value(i, c);
  }
  return t;
}

// theta_i and theta_o (degrees) at a cell centre.
void IncidentOutgoingDeg(const Grid& g, std::size_t idx, double* ti, double* to) {
  Vec3 wi, wo;
  FromHalfDiff(g.CellCentre(idx), 0.0, &wi, &wo);
  *ti = std::acos(std::clamp(wi.z, -1.0, 1.0)) * 180 / kPi;
  *to = std::acos(std::clamp(wo.z, -1.0, 1.0)) * 180 / kPi;
}

bool Finite(double v) { return std::isfinite(v); }

FitOptions StressOptions() {
  FitOptions o = LogLossUnpolished();
  o.max_iterations = 50;
  return o;
}

// The contract of FitResult (core/result.h): no NaN or Inf anywhere; a failure says why;
// a usable result lies inside the model's bounds; iterations bounded by the options.
void ExpectSane(const FitResult& r, const FitOptions& o, const std::string& what) {
  SCOPED_TRACE(what + " / " + r.model + " (" + ToString(r.status) + ": " + r.message + ")");
  ASSERT_EQ(r.params.size(), r.param_names.size());
  for (std::size_t k = 0; k < r.params.size(); ++k) {
    EXPECT_TRUE(Finite(r.params[k])) << r.param_names[k] << " = " << r.params[k];
  }
  EXPECT_TRUE(Finite(r.init_cost) && r.init_cost >= 0) << r.init_cost;
  EXPECT_TRUE(Finite(r.final_cost) && r.final_cost >= 0) << r.final_cost;
  for (double t : {r.times.load, r.times.prepare, r.times.init, r.times.solve, r.times.metrics}) {
    EXPECT_TRUE(Finite(t) && t >= 0) << t;
  }
  // One coarse and one full stage per start, each at most max_iterations.
  EXPECT_LE(r.iterations, 2 * o.max_iterations * std::max(1, r.starts));
  if (r.Failed()) {
    EXPECT_FALSE(r.message.empty()) << "a failed fit must say why";
    return;
  }
  const ModelInfo* m = FindModel(r.model);
  ASSERT_NE(m, nullptr);
  ASSERT_EQ(r.params.size(), m->params.size());
  for (std::size_t k = 0; k < r.params.size(); ++k) {
    EXPECT_GE(r.params[k], m->params[k].lower) << r.param_names[k];
    EXPECT_LE(r.params[k], m->params[k].upper) << r.param_names[k];
  }
  const FitMetrics& mt = r.metrics;
  if (mt.ok) {
    EXPECT_TRUE(Finite(mt.log_rmse) && mt.log_rmse >= 0) << mt.log_rmse;
    EXPECT_TRUE(Finite(mt.cbrt_rmse) && mt.cbrt_rmse >= 0) << mt.cbrt_rmse;
    EXPECT_TRUE(Finite(mt.rel_l2) && mt.rel_l2 >= 0) << mt.rel_l2;
    EXPECT_TRUE(Finite(mt.total_weight));
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(Finite(mt.worst.measured[c]) && Finite(mt.worst.predicted[c]));
    }
    EXPECT_GT(mt.cells, 0u);
  } else {
    EXPECT_FALSE(mt.problem.empty()) << "metrics not ok must say why";
  }
}

// Fits each model; returns the results (all checked with ExpectSane).
std::vector<FitResult> FitAll(const Table& t, const std::vector<std::string>& models,
                              const std::string& what, SampleOptions so = {},
                              FitOptions fo = StressOptions()) {
  std::vector<FitResult> out;
  for (const auto& model : models) {
    FitResult r;
    EXPECT_NO_THROW(r = FitTable(model, t, so, fo)) << what << " / " << model;
    r.model = r.model.empty() ? model : r.model;
    ExpectSane(r, fo, what);
    if (std::getenv("BRDFIT_STRESS_VERBOSE")) {  // the table in docs/reliability.md
      std::printf("| %s | %s | %s | %d | %.4g | %s |\n", what.c_str(), model.c_str(),
                  ToString(r.status), r.iterations, r.metrics.ok ? r.metrics.log_rmse : -1.0,
                  r.message.c_str());
    }
    out.push_back(r);
  }
  return out;
}

const std::vector<std::string> kModels = {"lambert", "ggx", "lambert+ggx", "lambert+ward",
                                          "lambert+lafortune"};

std::vector<double> LambertGgx(double kd, double ks, double alpha) {
  return {kd, kd, kd, ks, ks, ks, alpha};
}

// ---- the cases ------------------------------------------------------------------------------

TEST(NumericalStress, AlphaAtItsLowerBound) {
  // alpha = 1e-4: the lobe is far narrower than a bin; a few cells hold values ~1e7.
  const Table t = Synth("lambert+ggx", LambertGgx(0.3, 1.0, 1e-4));
  for (const auto& r : FitAll(t, {"ggx", "lambert+ggx"}, "alpha=1e-4")) EXPECT_FALSE(r.Failed());
}

TEST(NumericalStress, AlphaAtItsUpperBound) {
  const Table t = Synth("lambert+ggx", LambertGgx(0.3, 0.5, 1.0));
  for (const auto& r : FitAll(t, kModels, "alpha=1")) EXPECT_FALSE(r.Failed());
}

TEST(NumericalStress, GrazingOnlyData) {
  // Only cells with theta_i or theta_o beyond 80 degrees are valid.
  Table t = Synth("lambert+ggx", LambertGgx(0.3, 0.5, 0.2));
  std::size_t kept = 0;
  for (std::size_t i = 0; i < t.grid.NumCells(); ++i) {
    double ti, to;
    IncidentOutgoingDeg(t.grid, i, &ti, &to);
    if (ti <= 80 && to <= 80) t.valid[i] = 0;
    kept += t.valid[i];
  }
  ASSERT_GT(kept, 100u);
  // With the default 80-degree cut-off nothing is eligible: a clear failure, not a crash.
  for (const auto& r : FitAll(t, kModels, "grazing, cutoff 80")) {
    EXPECT_TRUE(r.Failed());
  }
  // With the cut-off opened, the grazing cells alone are fitted.
  SampleOptions so;
  so.cutoff_deg = 89.9;
  FitAll(t, kModels, "grazing, cutoff 89.9", so);
}

TEST(NumericalStress, RetroReflectionCellsOnly) {
  // Only theta_d bin 0 (wi within ~3 degrees of wo): the specular and retro directions coincide.
  Table t = Synth("lambert+ggx", LambertGgx(0.3, 0.5, 0.2));
  for (std::size_t i = 0; i < t.grid.NumCells(); ++i) {
    int ih, id, ip;
    t.grid.Unindex(i, &ih, &id, &ip);
    if (id != 0) t.valid[i] = 0;
  }
  ASSERT_GT(t.CountValid(), 100u);
  FitAll(t, kModels, "retro-reflection only");
}

TEST(NumericalStress, AllZeroTableWithEveryLoss) {
  const Table t = Filled([](std::size_t, int) { return 0.0; });
  for (const LossKind loss :
       {LossKind::kLog, LossKind::kCbrt, LossKind::kRel, LossKind::kL2, LossKind::kLogRatio}) {
    FitOptions fo = StressOptions();
    fo.loss = loss;
    FitAll(t, kModels, std::string("all zero, loss ") + ToString(loss), {}, fo);
  }
  // Lambert's weights all end at their lower bound 0, where the gradient points out of the
  // box: a KKT point, reported as converged (not as "no convergence after 0 iterations").
  const FitResult r = FitTable("lambert", t, {}, StressOptions());
  EXPECT_EQ(r.status, FitStatus::kConverged) << r.message;
  for (int c = 0; c < 3; ++c) EXPECT_EQ(r.params[c], 0.0);
}

TEST(NumericalStress, ConstantTableWithEveryLoss) {
  const Table t = Filled([](std::size_t, int) { return 0.3; });
  for (const LossKind loss :
       {LossKind::kLog, LossKind::kCbrt, LossKind::kRel, LossKind::kL2, LossKind::kLogRatio}) {
    FitOptions fo = StressOptions();
    fo.loss = loss;
    for (const auto& r : FitAll(t, kModels, std::string("constant, loss ") + ToString(loss), {},
                                fo)) {
      EXPECT_FALSE(r.Failed());
    }
  }
  // A constant f_r = 0.3 is Lambert with kd = 0.3 pi (within its bounds [0, 1]).
  const FitResult r = FitTable("lambert", t, {}, StressOptions());
  ASSERT_FALSE(r.Failed()) << r.message;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.params[c], 0.3 * kPi, 1e-6);
}

TEST(NumericalStress, SingleValidCell) {
  Table t = Synth("lambert+ggx", LambertGgx(0.3, 0.5, 0.2));
  const std::size_t keep = t.grid.Index(5, 4, 7);
  ASSERT_TRUE(t.valid[keep]);
  for (std::size_t i = 0; i < t.grid.NumCells(); ++i) t.valid[i] = i == keep;
  for (const LossKind loss : {LossKind::kLog, LossKind::kRel, LossKind::kLogRatio}) {
    FitOptions fo = StressOptions();
    fo.loss = loss;
    FitAll(t, kModels, std::string("single cell, loss ") + ToString(loss), {}, fo);
  }
}

TEST(NumericalStress, DynamicRange1e8To1e5) {
  // Diffuse 1e-8 / sr under a Beckmann lobe (alpha 0.02) peaking near 1e5 / sr; Beckmann's
  // Gaussian tails leave the diffuse floor visible (GGX's long tails would not).
  const Table t = Synth("lambert+beckmann", LambertGgx(1e-8 * kPi, 500.0, 0.02));
  double lo = HUGE_VAL, hi = 0;
  for (std::size_t i = 0; i < t.grid.NumCells(); ++i) {
    if (!t.valid[i]) continue;
    for (int c = 0; c < 3; ++c) {
      lo = std::min(lo, t.rgb[3 * i + c]);
      hi = std::max(hi, t.rgb[3 * i + c]);
    }
  }
  ASSERT_LT(lo, 2e-8);
  ASSERT_GT(hi, 1e4);
  for (const LossKind loss :
       {LossKind::kLog, LossKind::kCbrt, LossKind::kRel, LossKind::kL2, LossKind::kLogRatio}) {
    FitOptions fo = StressOptions();
    fo.loss = loss;
    for (const auto& r : FitAll(t, {"ggx", "lambert+ggx", "lambert+beckmann"},
                                std::string("range 1e-8..1e5, loss ") + ToString(loss), {}, fo)) {
      EXPECT_FALSE(r.Failed());
    }
  }
}

TEST(NumericalStress, HalfTheCellsNaN) {
  Table t = Synth("lambert+ggx", LambertGgx(0.3, 0.5, 0.2));
  std::size_t n_nan = 0, k = 0;
  for (std::size_t i = 0; i < t.grid.NumCells(); ++i) {
    if (!t.valid[i] || k++ % 2) continue;
    t.rgb[3 * i + 1] = std::numeric_limits<double>::quiet_NaN();
    ++n_nan;
  }
  // In an HDF5 table, NaN in a cell marked valid is bad input, named with the first such cell.
  const fs::path h5 = fuzz::ScratchDir() / "half-nan.h5";
  WriteHdf5Table(t, h5);
  try {
    ReadHdf5Table(h5);
    ADD_FAILURE() << "a table with NaN in valid cells was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("NaN at valid cell"), std::string::npos) << e.what();
  }
  // Masked NaN cells are missing cells: the file reads and fits.
  Table masked = t;
  for (std::size_t i = 0; i < masked.grid.NumCells(); ++i) {
    if (std::isnan(masked.rgb[3 * i + 1])) masked.valid[i] = 0;
  }
  WriteHdf5Table(masked, h5);
  const Table read = ReadHdf5Table(h5);
  for (const auto& r : FitAll(read, kModels, "50% NaN masked (HDF5)")) EXPECT_FALSE(r.Failed());
  // In memory (a table not from a file), NaN cells marked valid are dropped and counted.
  EXPECT_EQ(PrepareSamples(t, {}).counts.nonfinite, n_nan);
  for (const auto& r : FitAll(t, kModels, "50% NaN valid (in memory)")) EXPECT_FALSE(r.Failed());
}

TEST(NumericalStress, NinetyPercentMissing) {
  SynthOptions so;
  so.missing_fraction = 0.9;
  so.seed = 11;
  const Table t = Synth("lambert+ggx", LambertGgx(0.3, 0.5, 0.2), so);
  for (const auto& r : FitAll(t, kModels, "90% missing")) EXPECT_FALSE(r.Failed());
}

TEST(NumericalStress, EveryCellInvalid) {
  const Table t = Table::Empty(StressGrid());
  for (const auto& r : FitAll(t, kModels, "every cell invalid")) EXPECT_TRUE(r.Failed());
}

TEST(NumericalStress, PureNoiseWithEveryLoss) {
  // Log-normal values, sigma 3 (about 1e-4..1e4), independent per cell and channel.
  const Table t = Filled([](std::size_t i, int c) { return std::exp(3.0 * SynthNormal(5, c, i)); });
  for (const LossKind loss :
       {LossKind::kLog, LossKind::kCbrt, LossKind::kRel, LossKind::kL2, LossKind::kLogRatio}) {
    FitOptions fo = StressOptions();
    fo.loss = loss;
    fo.robust = RobustKind::kCauchy;
    FitAll(t, kModels, std::string("pure noise, loss ") + ToString(loss), {}, fo);
  }
}

}  // namespace
}  // namespace brdfit
