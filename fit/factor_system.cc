#include "fit/factor_system.h"

#include <fmt/core.h>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstring>

#include "fit/bin_measure.h"
#include "io/error.h"

namespace brdfit {

const char* ToString(FactorWeighting w) {
  return w == FactorWeighting::kSolidAngle ? "solid-angle" : "cell";
}

FactorWeighting FactorWeightingFromString(const std::string& s) {
  if (s == "solid-angle") return FactorWeighting::kSolidAngle;
  if (s == "cell") return FactorWeighting::kCell;
  throw InputError("unknown weighting '" + s + "' (expected solid-angle or cell)");
}

std::uint64_t HashMask(const std::vector<std::uint8_t>& mask) {
  // FNV-1a, 64 bit.
  std::uint64_t h = 14695981039346656037ull;
  for (std::uint8_t b : mask) {
    h ^= b;
    h *= 1099511628211ull;
  }
  return h ^ mask.size();
}

namespace {

using Triplet = Eigen::Triplet<double>;

// One row of A before merging duplicate columns (p(wi) and p(wo) may share knots).
struct RowEntries {
  int n = 0;
  std::array<int, 8> col{};
  std::array<double, 8> val{};
  void Add(int c, double v) {
    if (v == 0) return;
    for (int k = 0; k < n; ++k) {
      if (col[k] == c) {
        val[k] += v;
        return;
      }
    }
    col[n] = c;
    val[n] = v;
    ++n;
  }
  void Sort() {
    for (int a = 1; a < n; ++a) {  // insertion sort of <= 6 entries
      for (int b = a; b > 0 && col[b - 1] > col[b]; --b) {
        std::swap(col[b - 1], col[b]);
        std::swap(val[b - 1], val[b]);
      }
    }
  }
};

// FactorWeighting::kSolidAngle: the bin measure shared with the fits (fit/bin_measure.h),
// 8 pi [cos th_lo - cos th_hi] [(sin^2 td_hi - sin^2 td_lo) / 2] dphi_d, divided by its sum
// over the whole (theta_h, theta_d, phi_d) box, 8 pi * 1 * 1/2 * pi = 4 pi^2.
double CellSolidAngleWeight(const Grid& g, std::size_t idx) {
  int ih, id, ip;
  g.Unindex(idx, &ih, &id, &ip);
  return CellMeasure(g, ih, id, ip) / (4 * kPi * kPi);
}

// Second differences of a radial profile on k knots over rho in [0, 1]:
// lambda * integral (g'')^2 drho  ~  sum_k h (Delta^2 x_k / h^2)^2.
// The profile is a slice of an isotropic 2-D texture through the pole, i.e. an even function
// of rho (g'(0) = 0, which the disk maps preserve: smooth isotropic factors have a flat top).
// The row at the pole uses the mirrored knot x_-1 = x_1 and counts half (it is shared by the
// two halves of the diameter). Away from data the fill is then flat at the pole and linear
// towards the rim.
void AddProfileSmoothness(int offset, int k, double lambda, std::vector<Triplet>* t, int* row) {
  const double h = 1.0 / (k - 1);
  const double c = std::sqrt(lambda * h) / (h * h);
  const double c0 = std::sqrt(0.5) * c;
  t->emplace_back(*row, offset, -2 * c0);
  t->emplace_back(*row, offset + 1, 2 * c0);
  ++*row;
  for (int i = 1; i + 1 < k; ++i, ++*row) {
    t->emplace_back(*row, offset + i - 1, c);
    t->emplace_back(*row, offset + i, -2 * c);
    t->emplace_back(*row, offset + i + 1, c);
  }
}

// Thin-plate energy of an n x n texture over [0, 1]^2 (u = column, v = row, v periodic):
// lambda * integral (g_uu^2 + 2 g_uv^2 + g_vv^2) du dv. Its null space is the functions affine
// in u (constant in v), so texels no sample touches are filled by the smoothest continuation.
// (The bare 5-point Laplacian would leave every discrete harmonic function free at the edges.)
void AddTextureSmoothness(int offset, int n, double lambda, std::vector<Triplet>* t, int* row) {
  const double h = 1.0 / n;
  const double area = std::sqrt(lambda * h * h);
  const double c2 = area / (h * h);
  const double cm = std::sqrt(2.0) * area / (h * h);
  auto at = [&](int i, int j) { return offset + ((j % n + n) % n) * n + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (i >= 1 && i + 1 < n) {  // g_uu, theta_d clamps
        t->emplace_back(*row, at(i - 1, j), c2);
        t->emplace_back(*row, at(i, j), -2 * c2);
        t->emplace_back(*row, at(i + 1, j), c2);
        ++*row;
      }
      // g_vv, phi_d periodic
      t->emplace_back(*row, at(i, j - 1), c2);
      t->emplace_back(*row, at(i, j), -2 * c2);
      t->emplace_back(*row, at(i, j + 1), c2);
      ++*row;
      if (i + 1 < n) {  // g_uv
        t->emplace_back(*row, at(i + 1, j + 1), cm);
        t->emplace_back(*row, at(i + 1, j), -cm);
        t->emplace_back(*row, at(i, j + 1), -cm);
        t->emplace_back(*row, at(i, j), cm);
        ++*row;
      }
    }
  }
}

}  // namespace

std::shared_ptr<const FactorSystem> FactorSystem::Build(const Grid& grid,
                                                        const std::vector<std::uint8_t>& mask,
                                                        const FactorSystemOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  if (options.resolution < 4 || options.resolution > 1024) {
    throw InputError(fmt::format("resolution {} out of range [4, 1024]", options.resolution));
  }
  if (!(options.lambda > 0) || !std::isfinite(options.lambda)) {
    throw InputError(
        fmt::format("lambda must be a positive finite number (got {}); it fills "
                    "texels no sample touches",
                    options.lambda));
  }
  if (!(options.max_theta > 0) || options.max_theta > kPi / 2) {
    throw InputError("max theta must be in (0, 90] degrees");
  }
  if (mask.size() != grid.NumCells()) {
    throw InputError("mask size does not match the grid");
  }

  std::shared_ptr<FactorSystem> s(new FactorSystem);
  s->grid_ = grid;
  s->mask_ = mask;
  s->options_ = options;
  const int n = options.resolution;
  const int k = n;  // radial knots
  const bool mccool = options.param == FactorParam::kMcCool;
  s->n_p_ = k;
  s->n_q_ = mccool ? k : n * n;
  const int n_p = s->n_p_;

  // ---- data rows ----
  s->row_start_.push_back(0);
  double weight_sum = 0;
  for (std::size_t idx = 0; idx < grid.NumCells(); ++idx) {
    if (!mask[idx]) continue;
    const HalfDiffAngles a = grid.CellCentre(idx);
    Vec3 wi, wo;
    FromHalfDiff(a, 0.0, &wi, &wo);
    if (wi.z <= 0 || wo.z <= 0) continue;
    const double theta_i = std::acos(std::min(wi.z, 1.0));
    const double theta_o = std::acos(std::min(wo.z, 1.0));
    if (theta_i > options.max_theta || theta_o > options.max_theta) continue;
    RowEntries e;
    if (mccool) {
      // log f = log p(wi) + log q(wh) + log p(wo); each factor radial (factor_param.h).
      for (double th : {theta_i, theta_o}) {
        const Linear2 l = ProfileWeights(DiskRadius(FactorMap::kDiskParabolic, th), k);
        e.Add(l.index[0], l.weight[0]);
        e.Add(l.index[1], l.weight[1]);
      }
      const Linear2 l = ProfileWeights(DiskRadius(FactorMap::kDiskSqrtTheta, a.theta_h), k);
      e.Add(n_p + l.index[0], l.weight[0]);
      e.Add(n_p + l.index[1], l.weight[1]);
    } else {
      // log f = log p(wh) + log q(theta_d, phi_d).
      const Linear2 l = ProfileWeights(DiskRadius(FactorMap::kDiskSqrtTheta, a.theta_h), k);
      e.Add(l.index[0], l.weight[0]);
      e.Add(l.index[1], l.weight[1]);
      const Bilinear b = ThetaDPhiDLookup(a.theta_d, a.phi_d, n, n);
      for (int c = 0; c < 4; ++c) e.Add(n_p + b.index[c], b.weight[c]);
    }
    e.Sort();
    for (int c = 0; c < e.n; ++c) {
      s->col_.push_back(e.col[c]);
      s->val_.push_back(e.val[c]);
    }
    s->row_start_.push_back(static_cast<int>(s->col_.size()));
    s->row_cells_.push_back(static_cast<std::uint32_t>(idx));
    const double w = options.weighting == FactorWeighting::kSolidAngle
                         ? CellSolidAngleWeight(grid, idx)
                         : 1.0 / static_cast<double>(grid.NumCells());
    s->row_weight_.push_back(w);
    weight_sum += w;
  }
  const std::size_t rows = s->row_cells_.size();
  if (rows == 0 || !(weight_sum > 0)) {
    throw InputError(
        "no usable cell (every cell is masked, below the horizon or beyond the "
        "angle cut-off)");
  }

  // ---- normal matrix M = A^T W A + L^T L + g g^T ----
  const int n_unknowns = s->n_p_ + s->n_q_;
  Eigen::SparseMatrix<double> sqrt_w_a(static_cast<Eigen::Index>(rows), n_unknowns);
  {
    // Column-major copy of sqrt(W) A for the product (Eigen's sparse product accumulates each
    // result column densely: cost sum over rows of nnz^2).
    std::vector<Triplet> t;
    t.reserve(s->val_.size());
    for (std::size_t r = 0; r < rows; ++r) {
      const double sw = std::sqrt(s->row_weight_[r]);
      for (int e = s->row_start_[r]; e < s->row_start_[r + 1]; ++e) {
        t.emplace_back(static_cast<int>(r), s->col_[e], sw * s->val_[e]);
      }
    }
    sqrt_w_a.setFromTriplets(t.begin(), t.end());
  }
  Eigen::SparseMatrix<double> normal = sqrt_w_a.transpose() * sqrt_w_a;
  sqrt_w_a = Eigen::SparseMatrix<double>();

  std::vector<Triplet> lt;
  int lrow = 0;
  AddProfileSmoothness(0, k, options.lambda, &lt, &lrow);
  if (mccool) {
    AddProfileSmoothness(n_p, k, options.lambda, &lt, &lrow);
  } else {
    AddTextureSmoothness(n_p, n, options.lambda, &lt, &lrow);
  }
  // Gauge (docs/factorization.md §4): the data and smoothness terms are invariant along
  // (log p + c, log q - p_uses c); one row fixes c without changing the product.
  //  mccool:   log p(theta = 0) = 0, i.e. p(normal) = 1.
  //  halfdiff: mean of log q over the first theta_d column = 0, i.e. q(theta_d -> 0) ~ 1.
  if (mccool) {
    lt.emplace_back(lrow++, 0, 1.0);
  } else {
    for (int j = 0; j < n; ++j) lt.emplace_back(lrow, n_p + j * n, 1.0 / n);
    ++lrow;
  }
  Eigen::SparseMatrix<double> l(lrow, n_unknowns);
  l.setFromTriplets(lt.begin(), lt.end());
  s->normal_ = normal + Eigen::SparseMatrix<double>(l.transpose() * l);
  s->normal_.makeCompressed();

  s->ldlt_.compute(s->normal_);
  if (s->ldlt_.info() != Eigen::Success || !(s->ldlt_.vectorD().minCoeff() > 0) ||
      !s->ldlt_.vectorD().allFinite()) {
    throw InputError(
        "factorization system is singular (too few usable cells for the "
        "resolution, or lambda too small)");
  }
  s->build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

void FactorSystem::ApplyReduced(const Eigen::VectorXd& v, const std::vector<std::uint32_t>& removed,
                                Eigen::VectorXd* out) const {
  *out = normal_ * v;
  for (std::uint32_t r : removed) {
    double dot = 0;
    for (int e = row_start_[r]; e < row_start_[r + 1]; ++e) dot += val_[e] * v[col_[e]];
    const double s = row_weight_[r] * dot;
    for (int e = row_start_[r]; e < row_start_[r + 1]; ++e) (*out)[col_[e]] -= s * val_[e];
  }
}

bool FactorSystem::Solve(const Eigen::MatrixX3d& y, const std::vector<std::uint32_t>& removed,
                         Eigen::MatrixX3d* x, FactorSolveInfo* info) const {
  const std::size_t rows = row_cells_.size();
  assert(static_cast<std::size_t>(y.rows()) == rows);
  if (removed.size() > kMaxRemovedRows) return false;
  const int n = n_p_ + n_q_;
  // b = A^T W y over the kept rows.
  Eigen::MatrixX3d b = Eigen::MatrixX3d::Zero(n, 3);
  std::size_t next_removed = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    if (next_removed < removed.size() && removed[next_removed] == r) {
      ++next_removed;
      continue;
    }
    const double w = row_weight_[r];
    const double y0 = w * y(r, 0), y1 = w * y(r, 1), y2 = w * y(r, 2);
    for (int e = row_start_[r]; e < row_start_[r + 1]; ++e) {
      const double a = val_[e];
      double* bp = b.data() + col_[e];
      bp[0] += a * y0;
      bp[n] += a * y1;
      bp[2 * n] += a * y2;
    }
  }
  Eigen::MatrixX3d sol = ldlt_.solve(b);
  FactorSolveInfo local;
  local.removed_rows = removed.size();
  if (!removed.empty()) {
    // Preconditioned CG on (M - sum_removed w a a^T) x = b, preconditioner M^-1, started at
    // M^-1 b. The preconditioned operator is I minus a rank-|removed| term, so CG is exact in
    // at most |removed| + 1 steps; clustered spectra make it far fewer in practice.
    Eigen::VectorXd r, z, p, ap;
    for (int c = 0; c < 3; ++c) {
      Eigen::VectorXd xc = sol.col(c);
      ApplyReduced(xc, removed, &ap);
      r = b.col(c) - ap;
      const double b_norm = std::max(b.col(c).norm(), 1e-300);
      z = ldlt_.solve(r);
      p = z;
      double rz = r.dot(z);
      int it = 0;
      for (; it < kMaxPcgIterations && r.norm() > 1e-11 * b_norm; ++it) {
        ApplyReduced(p, removed, &ap);
        const double pap = p.dot(ap);
        if (!(pap > 0)) return false;
        const double alpha = rz / pap;
        xc += alpha * p;
        r -= alpha * ap;
        z = ldlt_.solve(r);
        const double rz_new = r.dot(z);
        p = z + (rz_new / rz) * p;
        rz = rz_new;
      }
      if (r.norm() > 1e-11 * b_norm) return false;
      local.pcg_iterations = std::max(local.pcg_iterations, it);
      sol.col(c) = xc;
    }
  }
  if (!sol.allFinite()) return false;
  *x = sol;
  if (info) *info = local;
  return true;
}

double FactorSystem::WeightedRms(const Eigen::MatrixX3d& y,
                                 const std::vector<std::uint32_t>& removed,
                                 const Eigen::MatrixX3d& x) const {
  double sum = 0, wsum = 0;
  std::size_t next_removed = 0;
  for (std::size_t r = 0; r < row_cells_.size(); ++r) {
    if (next_removed < removed.size() && removed[next_removed] == r) {
      ++next_removed;
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      double pred = 0;
      for (int e = row_start_[r]; e < row_start_[r + 1]; ++e) pred += val_[e] * x(col_[e], c);
      const double d = y(r, c) - pred;
      sum += row_weight_[r] * d * d;
    }
    wsum += 3 * row_weight_[r];
  }
  return wsum > 0 ? std::sqrt(sum / wsum) : 0.0;
}

std::shared_ptr<const FactorSystem> FactorSystemCache::GetOrBuild(
    const Grid& grid, const std::vector<std::uint8_t>& mask, const FactorSystemOptions& options,
    bool* hit) {
  const std::uint64_t h = HashMask(mask);
  std::lock_guard<std::mutex> lock(mu_);
  for (auto it = entries_.begin(); it != entries_.end(); ++it) {
    const FactorSystem& s = *it->system;
    if (it->mask_hash == h && s.grid() == grid && s.options() == options && s.mask() == mask) {
      entries_.splice(entries_.begin(), entries_, it);
      if (hit) *hit = true;
      return entries_.front().system;
    }
  }
  auto system = FactorSystem::Build(grid, mask, options);
  entries_.push_front({h, system});
  while (entries_.size() > capacity_) entries_.pop_back();
  if (hit) *hit = false;
  return system;
}

std::size_t FactorSystemCache::size() const {
  std::lock_guard<std::mutex> lock(mu_);
  return entries_.size();
}

void FactorSystemCache::Clear() {
  std::lock_guard<std::mutex> lock(mu_);
  entries_.clear();
}

}  // namespace brdfit
