// The compressed residual blocks (fit/block_cost.h) must give Ceres the same cost, gradient and
// Gauss-Newton matrix as the plain per-residual problem. Oracle: the residuals written out from
// the loss definitions, differentiated by central differences, robustified as
// ceres::Corrector does for concave losses (rows and residuals scaled by sqrt(rho')).
#include <ceres/loss_function.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>

#include "fit/fitter.h"
#include "fit/loss.h"
#include "fit/samples.h"
#include "fit_test_util.h"
#include "models/registry.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SynthModel;

double Transform(LossKind k, double x) {
  switch (k) {
    case LossKind::kLog:
      return std::log1p(x);
    case LossKind::kCbrt:
      return std::cbrt(x);
    case LossKind::kLogRatio:
      return std::log(x + kLogRatioEpsilon);
    default:
      return x;
  }
}

// Unweighted residuals e (3 per observation) at optimization-space point x.
Eigen::VectorXd Residuals(const ModelInfo& m, const Samples& s, const FitOptions& o,
                          const Eigen::VectorXd& x) {
  std::vector<double> p(x.size());
  for (int i = 0; i < x.size(); ++i) p[i] = m.params[i].log_scale ? std::exp(x[i]) : x[i];
  Eigen::VectorXd e(3 * s.NumObservations());
  for (std::size_t k = 0; k < s.NumSamples(); ++k) {
    double f[3];
    m.eval(p.data(), s.geometry[k], f);
    for (std::uint32_t ob = s.obs_begin[k]; ob < s.obs_begin[k + 1]; ++ob) {
      const double c = (o.cosine && !IsRatioLoss(o.loss)) ? s.cos_i[ob] : 1.0;
      for (int ch = 0; ch < 3; ++ch) {
        const double v = s.value[3 * ob + ch];
        double r = Transform(o.loss, f[ch] * c) - Transform(o.loss, v * c);
        if (o.loss == LossKind::kRel) r /= std::abs(v) + kRelEpsilon;
        e[3 * ob + ch] = r;
      }
    }
  }
  return e;
}

struct Case {
  std::string model;
  std::vector<std::string> truth, at;
};

TEST(NormalEquations, CompressedBlocksMatchPlainProblem) {
  const Grid g{16, 16, 32, ThetaHMapping::kSqrt};
  const std::vector<Case> cases = {
      {"lambert+ggx", {"ggx.alpha=0.1"}, {"ggx.alpha=0.13", "lambert.kd_g=0.3"}},
      {"lambert+cook-torrance",
       {"cook-torrance.alpha=0.2"},
       {"cook-torrance.alpha=0.15", "cook-torrance.f0=0.5"}},
      {"lambert+lafortune", {"lafortune.n=30"}, {"lafortune.n=24", "lafortune.cxy=-0.9"}},
      // Three lobes: each channel's rows go to a Gram matrix of its own columns
      // (fit/block_cost.h), summed into the whole one.
      {"lambert+lafortune+lafortune+lafortune",
       {"lafortune1.n=30", "lafortune2.n=4", "lafortune3.n=200"},
       {"lafortune1.n=24", "lafortune2.cxy=-0.6", "lafortune3.n=150", "lafortune3.rho_g=0.2"}},
  };
  for (const Case& c : cases) {
    const ModelInfo& m = *FindModel(c.model);
    const Table t = SynthModel(c.model, Params(c.model, c.truth), g, 0.1, 0.1, 9);
    SampleOptions so;
    so.cutoff_deg = 85;
    const Samples s = PrepareSamples(t, so);
    const std::vector<double> p = Params(c.model, c.at);
    Eigen::VectorXd x(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      x[i] = m.params[i].log_scale ? std::log(p[i]) : p[i];
    }
    for (const LossKind loss :
         {LossKind::kLog, LossKind::kCbrt, LossKind::kRel, LossKind::kL2, LossKind::kLogRatio}) {
      for (const RobustKind robust : {RobustKind::kNone, RobustKind::kHuber, RobustKind::kCauchy}) {
        FitOptions o = LogLossUnpolished();
        o.loss = loss;
        o.robust = robust;
        o.robust_scale = 0.02;
        const std::string what = c.model + " " + ToString(loss) + " " + ToString(robust);
        const LossData ld = PrepareLoss(s, o);
        const NormalEquations ne = EvaluateNormalEquations(c.model, s, ld, o, p);

        // Oracle.
        const Eigen::VectorXd e = Residuals(m, s, o, x);
        const int n = static_cast<int>(e.size()), P = static_cast<int>(x.size());
        Eigen::MatrixXd J(n, P);
        for (int i = 0; i < P; ++i) {
          const double h = 1e-6 * std::max(1.0, std::abs(x[i]));
          Eigen::VectorXd xp = x, xm = x;
          xp[i] += h;
          xm[i] -= h;
          J.col(i) = (Residuals(m, s, o, xp) - Residuals(m, s, o, xm)) / (2 * h);
        }
        std::unique_ptr<ceres::LossFunction> rho;
        if (robust == RobustKind::kHuber) rho = std::make_unique<ceres::HuberLoss>(0.02);
        if (robust == RobustKind::kCauchy) rho = std::make_unique<ceres::CauchyLoss>(0.02);
        double cost = 0;
        Eigen::VectorXd r(n);
        Eigen::MatrixXd Jc(n, P);
        int robust_regime = 0;
        for (int j = 0; j < n; ++j) {
          const double omega = s.weight[j / 3] / (3 * s.total_weight);
          double rr[3] = {e[j] * e[j], 1.0, 0.0};
          if (rho) rho->Evaluate(e[j] * e[j], rr);
          robust_regime += rr[1] < 0.99;
          ASSERT_LE(rr[2], 0.0);  // concave: Corrector's alpha = 0
          cost += omega * rr[0];
          r[j] = std::sqrt(omega * rr[1]) * e[j];
          Jc.row(j) = std::sqrt(omega * rr[1]) * J.row(j);
        }
        if (rho) {
          EXPECT_GT(robust_regime, n / 20) << what;
        }
        const Eigen::VectorXd grad = Jc.transpose() * r;
        const Eigen::MatrixXd jtj = Jc.transpose() * Jc;

        EXPECT_NEAR(ne.cost / cost, 1.0, 1e-10) << what;
        const double gscale = grad.cwiseAbs().maxCoeff();
        const double hscale = jtj.cwiseAbs().maxCoeff();
        for (int i = 0; i < P; ++i) {
          EXPECT_NEAR(ne.gradient[i], grad[i], 1e-6 * gscale) << what << " gradient " << i;
          for (int k = 0; k < P; ++k) {
            EXPECT_NEAR(ne.jtj[i * P + k], jtj(i, k), 1e-6 * hscale)
                << what << " jtj " << i << "," << k;
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace brdfit
