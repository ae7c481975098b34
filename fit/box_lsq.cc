#include "fit/box_lsq.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace brdfit {

namespace {

double Objective(const Eigen::MatrixXd& N, const Eigen::VectorXd& b, const Eigen::VectorXd& x) {
  return x.dot(N * x) - 2.0 * b.dot(x);
}

Eigen::VectorXd Enumerate(const Eigen::MatrixXd& N, const Eigen::VectorXd& b,
                          const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  const int k = static_cast<int>(b.size());
  int combos = 1;
  for (int i = 0; i < k; ++i) combos *= 3;
  Eigen::VectorXd best = lo.cwiseMax(Eigen::VectorXd::Zero(k)).cwiseMin(hi);
  for (int i = 0; i < k; ++i) {
    if (!std::isfinite(best[i])) best[i] = 0.0;
  }
  double best_q = Objective(N, b, best);
  // q is convex (N positive semi-definite): an unconstrained minimizer inside the box is the
  // constrained one, and the 3^k enumeration is not needed (the common case, the initializer's
  // weights away from their bounds; ~10x faster for k = 4).
  // That is the enumeration's first assignment (code 0, every variable free), so the loop
  // starts after it.
  {
    const Eigen::VectorXd x = N.completeOrthogonalDecomposition().solve(b);
    bool inside = true;
    for (int i = 0; i < k; ++i) {
      inside = inside && std::isfinite(x[i]) && x[i] >= lo[i] && x[i] <= hi[i];
    }
    if (inside) {
      const double q = Objective(N, b, x);
      if (q < best_q) return x;
    }
  }
  // The buffers and decompositions of every free-set size, made once per call rather than per
  // assignment (80 of them for k = 4): the same decompositions of the same matrices (compute()
  // is what the constructor runs), so the same bits.
  std::vector<int> state(k);
  std::vector<int> free_idx;
  free_idx.reserve(static_cast<std::size_t>(k));
  Eigen::VectorXd x(k);
  std::vector<Eigen::MatrixXd> nffs(static_cast<std::size_t>(k) + 1);
  std::vector<Eigen::VectorXd> rhss(static_cast<std::size_t>(k) + 1), xfs(nffs.size());
  std::vector<Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>> cods;
  cods.reserve(nffs.size());
  for (int nf = 0; nf <= k; ++nf) {
    nffs[static_cast<std::size_t>(nf)].resize(nf, nf);
    rhss[static_cast<std::size_t>(nf)].resize(nf);
    xfs[static_cast<std::size_t>(nf)].resize(nf);
    cods.emplace_back(nf, nf);
  }
  for (int code = 1; code < combos; ++code) {
    int c = code;
    bool skip = false;
    free_idx.clear();
    x.setZero();
    for (int i = 0; i < k; ++i) {
      state[i] = c % 3;  // 0 free, 1 at lower, 2 at upper
      c /= 3;
      if (state[i] == 0) {
        free_idx.push_back(i);
      } else {
        const double v = state[i] == 1 ? lo[i] : hi[i];
        if (!std::isfinite(v)) skip = true;
        x[i] = v;
      }
    }
    if (skip) continue;
    const int nf = static_cast<int>(free_idx.size());
    if (nf > 0) {
      Eigen::MatrixXd& nff = nffs[static_cast<std::size_t>(nf)];
      Eigen::VectorXd& rhs = rhss[static_cast<std::size_t>(nf)];
      for (int a = 0; a < nf; ++a) {
        rhs[a] = b[free_idx[a]];
        for (int i = 0; i < k; ++i) {
          if (state[i] != 0) rhs[a] -= N(free_idx[a], i) * x[i];
        }
        for (int bb = 0; bb < nf; ++bb) nff(a, bb) = N(free_idx[a], free_idx[bb]);
      }
      auto& cod = cods[static_cast<std::size_t>(nf)];
      cod.compute(nff);
      Eigen::VectorXd& xf = xfs[static_cast<std::size_t>(nf)];
      xf = cod.solve(rhs);
      for (int a = 0; a < nf; ++a) x[free_idx[a]] = xf[a];
    }
    bool feasible = true;
    for (int i = 0; i < k; ++i) {
      if (!std::isfinite(x[i]) || x[i] < lo[i] || x[i] > hi[i]) feasible = false;
    }
    if (!feasible) continue;
    const double q = Objective(N, b, x);
    if (q < best_q) {
      best_q = q;
      best = x;
    }
  }
  return best;
}

Eigen::VectorXd GaussSeidel(const Eigen::MatrixXd& N, const Eigen::VectorXd& b,
                            const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  const int k = static_cast<int>(b.size());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(k).cwiseMax(lo).cwiseMin(hi);
  for (int sweep = 0; sweep < 200; ++sweep) {
    for (int i = 0; i < k; ++i) {
      if (!(N(i, i) > 0)) continue;
      const double r = b[i] - N.row(i).dot(x) + N(i, i) * x[i];
      x[i] = std::clamp(r / N(i, i), lo[i], hi[i]);
    }
  }
  return x;
}

}  // namespace

Eigen::VectorXd BoxLeastSquares(const Eigen::MatrixXd& N, const Eigen::VectorXd& b,
                                const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  if (b.size() == 0) return Eigen::VectorXd();
  return b.size() <= 5 ? Enumerate(N, b, lo, hi) : GaussSeidel(N, b, lo, hi);
}

}  // namespace brdfit
