#include "factor/factor_refine.h"

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "fit/loss.h"

namespace brdfit {
namespace {

// Above this log value a texel product is taken as diverged (e^80 ~ 5e34 1/sr).
constexpr double kMaxLog = 80;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kMaxTerms = 16;
// Unknowns of one term up to which a term's start is solved densely on the refinement's rows.
constexpr int kDenseStartLimit = 1024;

// The rows the refinement uses: every stride-th row of the system with finite values, their
// sparse entries copied into one compact CSR (the strided rows of the system are far apart in
// memory: reading them in place cost a cache miss per array per row).
struct RowSet {
  std::vector<int> start{0};  // compact CSR: entries of row i in [start[i], start[i + 1])
  std::vector<int> col;
  std::vector<double> val;
  std::vector<double> w;
  RowValues m;
  double weight_sum = 0;
  std::size_t size() const { return w.size(); }
};

RowSet PickRows(const FactorSystem& sys, const Table& table, std::size_t max_rows) {
  const std::size_t n = sys.num_rows();
  const std::size_t stride =
      std::max<std::size_t>(1, (n + max_rows - 1) / std::max<std::size_t>(1, max_rows));
  RowSet s;
  std::vector<std::array<double, 3>> m;
  for (std::size_t r = 0; r < n; r += stride) {
    const double* v = table.Value(sys.row_cells()[r]);
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) continue;
    for (int j = sys.row_start()[r]; j < sys.row_start()[r + 1]; ++j) {
      s.col.push_back(sys.cols()[j]);
      s.val.push_back(sys.vals()[j]);
    }
    s.start.push_back(static_cast<int>(s.col.size()));
    s.w.push_back(sys.row_weights()[r] * static_cast<double>(stride));
    s.weight_sum += s.w.back();
    m.push_back({v[0], v[1], v[2]});
  }
  s.m.resize(static_cast<Eigen::Index>(m.size()), 3);
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (int c = 0; c < 3; ++c) s.m(static_cast<Eigen::Index>(i), c) = m[i][c];
  }
  return s;
}

// a_r^T x for one block of unknowns: row r of the system, or row i of a RowSet.
inline double RowLog(const FactorSystem& sys, std::uint32_t r, const double* x) {
  const int b = sys.row_start()[r], e = sys.row_start()[r + 1];
  double s = 0;
  for (int j = b; j < e; ++j) s += sys.vals()[j] * x[sys.cols()[j]];
  return s;
}
inline double RowLog(const RowSet& rows, std::size_t i, const double* x) {
  double s = 0;
  for (int j = rows.start[i]; j < rows.start[i + 1]; ++j) s += rows.val[j] * x[rows.col[j]];
  return s;
}

// The data residual of one row and its derivative in f (w: the row's weight):
//   rel:      sqrt(w) (f - m) / (|m| + eps)                 (fit/loss.h, Sun et al. 2018)
//   logratio: sqrt(w) (ln(f + eps) - ln(m + eps))           (fit/loss.h GuardedLogOffset)
// written as scale (f - target) and scale (ln(f + eps) - target) with the per-row parts,
// target and scale, computed once (DataTerms).
struct DataTerms {
  RowValues target, scale;
};

DataTerms MakeDataTerms(RefineLoss loss, const RowSet& rows) {
  DataTerms t{rows.m, rows.m};
  for (Eigen::Index i = 0; i < rows.m.rows(); ++i) {
    const double sw = std::sqrt(rows.w[static_cast<std::size_t>(i)]);
    for (int c = 0; c < 3; ++c) {
      const double m = rows.m(i, c);
      t.target(i, c) = loss == RefineLoss::kRel ? m : GuardedLogOffset(m);
      t.scale(i, c) = loss == RefineLoss::kRel ? sw / (std::abs(m) + kRelEpsilon) : sw;
    }
  }
  return t;
}

inline double Residual(RefineLoss loss, double f, double target, double scale, double* dres_df) {
  if (loss == RefineLoss::kRel) {
    *dres_df = scale;
    return scale * (f - target);
  }
  // f >= 0 here (a sum of exponentials and d >= 0): the logarithm's own branch.
  *dres_df = scale / (f + kLogRatioEpsilon);
  return scale * (std::log(f + kLogRatioEpsilon) - target);
}

// One channel's problem. Unknowns theta = [x_0 (n), ..., x_{K-1} (n), d (if diffuse)].
class ChannelProblem {
 public:
  ChannelProblem(const FactorSystem& sys, const RowSet& rows, const DataTerms& data, int channel,
                 int rank, bool diffuse, RefineLoss loss, const Eigen::SparseMatrix<double>& sts)
      : rows_(rows),
        data_(data),
        ch_(channel),
        rank_(rank),
        diffuse_(diffuse),
        loss_(loss),
        sts_(sts) {
    n_ = sys.num_p() + sys.num_q();
    nt_ = rank_ * n_ + (diffuse_ ? 1 : 0);
  }
  int num_unknowns() const { return nt_; }

  // Data part of the objective only (sum of squared residuals), for reporting.
  double DataCost(const Eigen::VectorXd& th) const {
    double cost = 0;
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      double f = diffuse_ ? th[nt_ - 1] : 0.0;
      for (int k = 0; k < rank_; ++k) {
        const double lg = RowLog(rows_, i, th.data() + k * n_);
        if (!(lg <= kMaxLog)) return kInf;
        f += std::exp(lg);
      }
      double unused;
      const double res = Residual(loss_, f, data_.target(static_cast<Eigen::Index>(i), ch_),
                                  data_.scale(static_cast<Eigen::Index>(i), ch_), &unused);
      cost += res * res;
    }
    return cost;
  }

  double Cost(const Eigen::VectorXd& th) const {
    double cost = DataCost(th);
    for (int k = 0; k < rank_; ++k) {
      const auto x = th.segment(k * n_, n_);
      cost += x.dot(sts_ * x);
    }
    return cost;
  }

  // Levenberg-Marquardt from *th; returns the iterations taken. A trial is costed first and
  // linearized only if accepted (linearizing every trial was slower: many are rejected). The
  // damping follows the gain ratio rho = actual / predicted reduction (Nielsen 1999; Madsen,
  // Nielsen & Tingleff 2004, "Methods for Non-Linear Least Squares Problems", eq. 3.15):
  // accepted: mu *= max(1/3, 1 - (2 rho - 1)^3), nu = 2; rejected: mu *= nu, nu *= 2.
  int Minimize(Eigen::VectorXd* th, int max_iterations, std::size_t dense_limit, double tolerance) {
    const bool dense = static_cast<std::size_t>(nt_) <= dense_limit;
    double cost = Linearize(*th, dense);
    if (!std::isfinite(cost)) return 0;
    double mu = 1e-4, nu = 2;
    int it = 0;
    for (; it < max_iterations; ++it) {
      const Eigen::VectorXd step = dense ? DenseStep(mu) : SparseStep(mu);
      Eigen::VectorXd trial = *th + step;
      if (diffuse_) trial[nt_ - 1] = std::max(0.0, trial[nt_ - 1]);
      const double c = trial.allFinite() ? Cost(trial) : kInf;
      if (c < cost) {
        // cost = |r|^2: its quadratic model at th is cost + 2 g.s + s.H s.
        const Eigen::VectorXd s = trial - *th;
        const double hs = dense ? s.dot(h_.selfadjointView<Eigen::Upper>() * s)
                                : s.dot(hs_.selfadjointView<Eigen::Upper>() * s);
        const double predicted = -(2 * g_.dot(s) + hs);
        const double rho = predicted > 0 ? (cost - c) / predicted : 0.0;
        const double gain = (cost - c) / cost;
        *th = trial;
        mu = std::max(mu * std::max(1.0 / 3, 1 - std::pow(2 * rho - 1, 3)), 1e-12);
        nu = 2;
        if (gain < tolerance) {
          ++it;
          break;
        }
        cost = Linearize(*th, dense);
      } else {
        mu *= nu;
        nu *= 2;
        if (mu > 1e10) break;
      }
    }
    return it;
  }

 private:
  // Gradient g = J^T r + S^T S x and H = J^T J + S^T S, dense or in a sparse upper pattern.
  // Returns the cost.
  double Linearize(const Eigen::VectorXd& th, bool dense) {
    g_.setZero(nt_);
    diag_.setZero(nt_);
    if (dense) {
      h_.setZero(nt_, nt_);
    } else {
      if (!have_pattern_) BuildPattern();
      std::fill(hs_.valuePtr(), hs_.valuePtr() + hs_.nonZeros(), 0.0);
    }
    const std::size_t rows = rows_.size();
    double ce[kMaxTerms + 1];
    std::vector<int> idx;
    std::vector<double> val;
    double cost = 0;
    for (std::size_t i = 0; i < rows; ++i) {
      double f = diffuse_ ? th[nt_ - 1] : 0.0;
      for (int k = 0; k < rank_; ++k) {
        const double lg = RowLog(rows_, i, th.data() + k * n_);
        if (!(lg <= kMaxLog)) return kInf;
        ce[k] = std::exp(lg);
        f += ce[k];
      }
      double s;
      const double res = Residual(loss_, f, data_.target(static_cast<Eigen::Index>(i), ch_),
                                  data_.scale(static_cast<Eigen::Index>(i), ch_), &s);
      for (int k = 0; k < rank_; ++k) ce[k] *= s;
      ce[rank_] = s;
      cost += res * res;
      idx.clear();
      val.clear();
      const int b = rows_.start[i], e = rows_.start[i + 1];
      for (int k = 0; k < rank_; ++k) {
        for (int j = b; j < e; ++j) {
          idx.push_back(k * n_ + rows_.col[j]);
          val.push_back(ce[k] * rows_.val[j]);
        }
      }
      if (diffuse_) {
        idx.push_back(nt_ - 1);
        val.push_back(s);
      }
      for (std::size_t a = 0; a < idx.size(); ++a) {
        g_[idx[a]] += val[a] * res;
        diag_[idx[a]] += val[a] * val[a];
        // idx is ascending (columns sorted per row, blocks in order): upper triangle.
        if (dense) {
          for (std::size_t c = a; c < idx.size(); ++c) h_(idx[a], idx[c]) += val[a] * val[c];
        } else {
          for (std::size_t c = a; c < idx.size(); ++c) SparseAt(idx[a], idx[c]) += val[a] * val[c];
        }
      }
    }
    for (int k = 0; k < rank_; ++k) {
      const auto x = th.segment(k * n_, n_);
      const Eigen::VectorXd sx = sts_ * x;
      cost += x.dot(sx);
      g_.segment(k * n_, n_) += sx;
      for (int j = 0; j < sts_.outerSize(); ++j) {
        for (Eigen::SparseMatrix<double>::InnerIterator itr(sts_, j); itr; ++itr) {
          const int a = k * n_ + static_cast<int>(itr.row()),
                    c = k * n_ + static_cast<int>(itr.col());
          if (a == c) diag_[a] += itr.value();
          if (a <= c) (dense ? h_(a, c) : SparseAt(a, c)) += itr.value();
        }
      }
    }
    return cost;
  }

  Eigen::VectorXd Damping(double mu) const {
    const double floor = 1e-12 * std::max(1e-300, diag_.maxCoeff());
    return mu * diag_.cwiseMax(floor);
  }

  Eigen::VectorXd DenseStep(double mu) const {
    // H + mu D is symmetric positive definite (S^T S pins the gauge, mu D > 0): Cholesky.
    Eigen::MatrixXd a = h_;
    a.diagonal() += Damping(mu);
    Eigen::LLT<Eigen::MatrixXd, Eigen::Upper> llt(a);
    if (llt.info() != Eigen::Success) return Eigen::VectorXd::Zero(nt_);
    return llt.solve(-g_);
  }

  Eigen::VectorXd SparseStep(double mu) {
    Eigen::SparseMatrix<double> a = hs_;
    const Eigen::VectorXd damp = Damping(mu);
    for (int j = 0; j < nt_; ++j) a.coeffRef(j, j) += damp[j];
    if (!ldlt_) {
      ldlt_ = std::make_unique<SparseLdlt>();
      ldlt_->analyzePattern(a);
    }
    ldlt_->factorize(a);
    if (ldlt_->info() != Eigen::Success) return Eigen::VectorXd::Zero(nt_);
    return ldlt_->solve(-g_);
  }

  // The upper-triangular pattern of J^T J + S^T S (+ the diagonal), values zero.
  void BuildPattern() {
    using Triplet = Eigen::Triplet<double>;
    std::vector<Triplet> t;
    std::vector<int> idx;
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      idx.clear();
      for (int k = 0; k < rank_; ++k) {
        for (int j = rows_.start[i]; j < rows_.start[i + 1]; ++j)
          idx.push_back(k * n_ + rows_.col[j]);
      }
      if (diffuse_) idx.push_back(nt_ - 1);
      for (std::size_t x = 0; x < idx.size(); ++x) {
        for (std::size_t y = x; y < idx.size(); ++y) t.emplace_back(idx[x], idx[y], 1.0);
      }
    }
    for (int k = 0; k < rank_; ++k) {
      for (int j = 0; j < sts_.outerSize(); ++j) {
        for (Eigen::SparseMatrix<double>::InnerIterator itr(sts_, j); itr; ++itr) {
          if (itr.row() <= itr.col()) {
            t.emplace_back(k * n_ + static_cast<int>(itr.row()),
                           k * n_ + static_cast<int>(itr.col()), 1.0);
          }
        }
      }
    }
    for (int j = 0; j < nt_; ++j) t.emplace_back(j, j, 1.0);
    hs_.resize(nt_, nt_);
    hs_.setFromTriplets(t.begin(), t.end());
    hs_.makeCompressed();
    have_pattern_ = true;
  }

  // H(a, c), a <= c, in the compressed upper pattern.
  double& SparseAt(int a, int c) {
    const int* begin = hs_.innerIndexPtr() + hs_.outerIndexPtr()[c];
    const int* end = hs_.innerIndexPtr() + hs_.outerIndexPtr()[c + 1];
    const int* it = std::lower_bound(begin, end, a);
    return hs_.valuePtr()[it - hs_.innerIndexPtr()];
  }

  const RowSet& rows_;
  const DataTerms& data_;
  int ch_, rank_;
  bool diffuse_;
  RefineLoss loss_;
  const Eigen::SparseMatrix<double>& sts_;
  int n_ = 0, nt_ = 0;
  Eigen::VectorXd g_, diag_;
  Eigen::MatrixXd h_;               // dense H (upper), few unknowns
  Eigen::SparseMatrix<double> hs_;  // sparse H (upper), many unknowns
  using SparseLdlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper>;
  std::unique_ptr<SparseLdlt> ldlt_;  // (not movable itself)
  bool have_pattern_ = false;
};

// The model value d + sum_k exp(a_r^T x_k) of `n` rows (channels as columns), row_log(r, x)
// giving a_r^T x: every row of the system, or the refinement's rows.
template <class RowLogFn>
RowValues ModelValues(std::size_t n, RowLogFn row_log, const std::vector<Eigen::MatrixX3d>& terms,
                      const std::array<double, 3>& d) {
  RowValues f(static_cast<Eigen::Index>(n), 3);
  for (int c = 0; c < 3; ++c) f.col(c).setConstant(d[c]);
  for (const auto& x : terms) {
    for (int c = 0; c < 3; ++c) {
      const double* xc = x.col(c).data();  // column-major: a channel's unknowns are contiguous
      for (std::size_t r = 0; r < n; ++r) {
        f(static_cast<Eigen::Index>(r), c) += std::exp(std::min(kMaxLog, row_log(r, xc)));
      }
    }
  }
  return f;
}

// The log-linear solve of max(m - f, floor * m) (rows in `removed` ignored).
Eigen::MatrixX3d SolveRemainder(const FactorSystem& sys, const Table& table, const RowValues& f,
                                double floor, const std::vector<std::uint32_t>& removed,
                                const Eigen::MatrixX3d& fallback) {
  RowValues y(static_cast<Eigen::Index>(sys.num_rows()), 3);
  std::size_t next = 0;
  for (std::size_t r = 0; r < sys.num_rows(); ++r) {
    if (next < removed.size() && removed[next] == r) {
      ++next;
      y.row(static_cast<Eigen::Index>(r)).setZero();
      continue;
    }
    const double* v = table.Value(sys.row_cells()[r]);
    for (int c = 0; c < 3; ++c) {
      y(static_cast<Eigen::Index>(r), c) =
          std::log(std::max(v[c] - f(static_cast<Eigen::Index>(r), c), floor * v[c]));
    }
  }
  Eigen::MatrixX3d x;
  FactorSolveInfo info;
  if (!sys.Solve(y, removed, &x, &info) || !x.allFinite()) return fallback;
  return x;
}

// The log-linear solve of max(m - f, floor * m) on the refinement's rows only:
//   (A_s^T W_s A_s + S^T S) x = A_s^T W_s y_s,
// the cached system's normal equations (factor_system.h) restricted to the rows the refinement
// minimizes over, solved densely (one matrix for the three channels). For systems with few
// unknowns (mccool's radial profiles): a pass over these rows instead of every cell's, which
// cost ~60 ms per start at MERL resolution. Rows with a channel <= 0 are left out, as Solve
// leaves out `removed`.
Eigen::MatrixX3d SolveRemainderOnRows(const RowSet& rows, const Eigen::SparseMatrix<double>& sts,
                                      int n, const RowValues& f, double floor,
                                      const Eigen::MatrixX3d& fallback) {
  Eigen::MatrixXd a = Eigen::MatrixXd(sts);
  Eigen::MatrixX3d b = Eigen::MatrixX3d::Zero(n, 3);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    if (!(rows.m(ii, 0) > 0 && rows.m(ii, 1) > 0 && rows.m(ii, 2) > 0)) continue;
    double y[3];
    for (int c = 0; c < 3; ++c) {
      y[c] = std::log(std::max(rows.m(ii, c) - f(ii, c), floor * rows.m(ii, c)));
    }
    const double w = rows.w[i];
    for (int j = rows.start[i]; j < rows.start[i + 1]; ++j) {
      const double wa = w * rows.val[j];
      for (int c = 0; c < 3; ++c) b(rows.col[j], c) += wa * y[c];
      for (int k = rows.start[i]; k < rows.start[i + 1]; ++k) {
        a(rows.col[j], rows.col[k]) += wa * rows.val[k];
      }
    }
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(a);
  if (llt.info() != Eigen::Success) return fallback;
  const Eigen::MatrixX3d x = llt.solve(b);
  return x.allFinite() ? x : fallback;
}

double RelRms(const std::vector<ChannelProblem>& problems,
              const std::vector<Eigen::VectorXd>& theta, double weight_sum) {
  double sum = 0;
  for (std::size_t c = 0; c < problems.size(); ++c) sum += problems[c].DataCost(theta[c]);
  return std::sqrt(sum / (3 * weight_sum));
}

}  // namespace

RefineResult RefineFactorization(const FactorSystem& sys, const Table& table,
                                 const Eigen::MatrixX3d& x0,
                                 const std::vector<std::uint32_t>& removed,
                                 const RefineOptions& options) {
  const int n = sys.num_p() + sys.num_q();
  const int rank = std::clamp(options.rank, 1, kMaxTerms);
  const RowSet rows = PickRows(sys, table, options.max_rows);
  const DataTerms data = MakeDataTerms(options.loss, rows);
  RefineResult out;
  out.rows = rows.size();
  out.terms.push_back(x0);
  if (rows.size() == 0 || !(rows.weight_sum > 0)) return out;
  const Eigen::SparseMatrix<double> sts =
      Eigen::SparseMatrix<double>(sys.smoothing().transpose() * sys.smoothing());

  // Start: the log-linear solution alone.
  {
    std::vector<ChannelProblem> p;
    std::vector<Eigen::VectorXd> th;
    for (int c = 0; c < 3; ++c) {
      p.emplace_back(sys, rows, data, c, 1, false, options.loss, sts);
      th.push_back(x0.col(c));
    }
    out.rel_rms_start = RelRms(p, th, rows.weight_sum);
    for (int c = 0; c < 3; ++c) out.objective_start += p[c].Cost(th[c]);
  }

  // A term's start, the log-linear solve of what d and `terms` leave: on the refinement's rows
  // when a term's unknowns are few (a dense solve), on every row through the cached system
  // otherwise.
  const auto solve_remainder = [&](const std::vector<Eigen::MatrixX3d>& terms,
                                   const std::array<double, 3>& d, double floor,
                                   const Eigen::MatrixX3d& fallback) {
    if (n <= kDenseStartLimit) {
      const RowValues f = ModelValues(
          rows.size(), [&](std::size_t i, const double* x) { return RowLog(rows, i, x); }, terms,
          d);
      return SolveRemainderOnRows(rows, sts, n, f, floor, fallback);
    }
    const RowValues f = ModelValues(
        sys.num_rows(),
        [&](std::size_t r, const double* x) {
          return RowLog(sys, static_cast<std::uint32_t>(r), x);
        },
        terms, d);
    return SolveRemainder(sys, table, f, floor, removed, fallback);
  };
  std::array<double, 3> d{0, 0, 0};
  if (options.diffuse) {
    // d starts at half the 5 % quantile of the measured values, the term on what is left.
    for (int c = 0; c < 3; ++c) {
      std::vector<double> v(rows.m.rows());
      for (Eigen::Index i = 0; i < rows.m.rows(); ++i) v[i] = rows.m(i, c);
      auto q = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 20);
      std::nth_element(v.begin(), q, v.end());
      d[c] = std::max(0.0, 0.5 * *q);
    }
    out.terms[0] = solve_remainder({}, d, 0.25, x0);
  }

  for (int k = 1; k <= rank; ++k) {
    if (k > 1) {
      const Eigen::MatrixX3d start = out.terms.back().array() + std::log(0.1);
      out.terms.push_back(solve_remainder(out.terms, d, 0.02, start));
    }
    for (int c = 0; c < 3; ++c) {
      ChannelProblem p(sys, rows, data, c, k, options.diffuse, options.loss, sts);
      Eigen::VectorXd th(p.num_unknowns());
      for (int t = 0; t < k; ++t) th.segment(t * n, n) = out.terms[t].col(c);
      if (options.diffuse) th[p.num_unknowns() - 1] = d[c];
      if (k > 1) {
        // The deflated start can be worse than the rank k-1 solution it extends; then the new
        // term starts as 1 % of the previous one instead, so that rank k starts no worse than
        // rank k-1 ended (LM only descends).
        Eigen::VectorXd alt = th;
        alt.segment((k - 1) * n, n) = out.terms[k - 2].col(c).array() + std::log(0.01);
        if (p.Cost(alt) < p.Cost(th)) th = alt;
      }
      out.iterations +=
          p.Minimize(&th, options.max_iterations, options.dense_limit, options.tolerance);
      for (int t = 0; t < k; ++t) out.terms[t].col(c) = th.segment(t * n, n);
      if (options.diffuse) d[c] = th[p.num_unknowns() - 1];
    }
    if (k < rank) out.lower_ranks.push_back({d, out.terms});
  }
  out.diffuse = d;

  std::vector<ChannelProblem> p;
  std::vector<Eigen::VectorXd> th;
  for (int c = 0; c < 3; ++c) {
    p.emplace_back(sys, rows, data, c, rank, options.diffuse, options.loss, sts);
    Eigen::VectorXd t(p.back().num_unknowns());
    for (int k = 0; k < rank; ++k) t.segment(k * n, n) = out.terms[k].col(c);
    if (options.diffuse) t[t.size() - 1] = d[c];
    th.push_back(std::move(t));
  }
  out.rel_rms = RelRms(p, th, rows.weight_sum);
  for (int c = 0; c < 3; ++c) out.objective += p[c].Cost(th[c]);
  for (const auto& x : out.terms) {
    if (!x.allFinite()) throw std::runtime_error("factorization refinement diverged (non-finite)");
  }
  if (!std::isfinite(d[0] + d[1] + d[2])) {
    throw std::runtime_error("factorization refinement diverged (non-finite diffuse value)");
  }
  return out;
}

}  // namespace brdfit
