#include "factor/factor_system.h"

#include <fmt/core.h>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "fit/bin_measure.h"

namespace brdfit {

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
// over the whole (theta_h, theta_d, phi_d) box, 8 pi * 1 * 1/2 * pi = 4 pi^2. It does not
// depend on phi_d.
double CellSolidAngleWeight(const Grid& g, int ih, int id) {
  return CellMeasure(g, ih, id, 0) / (4 * kPi * kPi);
}

// Accumulates M = sum_r w_r a_r a_r^T without forming A: pairs involving one of the first
// `n_dense` unknowns (the radial profiles) go to a dense n x n_dense block; pairs of texel
// unknowns (bilinear neighbours) to a short list per texel.
class NormalAccumulator {
 public:
  NormalAccumulator(int n, int n_dense, int max_neighbours)
      : n_(n),
        n_dense_(n_dense),
        max_nb_(max_neighbours),
        dense_(Eigen::MatrixXd::Zero(n, n_dense)),
        nb_count_(n - n_dense, 0),
        nb_col_(static_cast<std::size_t>(n - n_dense) * max_neighbours),
        nb_val_(nb_col_.size(), 0.0) {}

  void Add(const int* col, const double* val, int cnt, double w) {
    for (int x = 0; x < cnt; ++x) {
      const double wx = w * val[x];
      for (int y = 0; y < cnt; ++y) {
        const int i = col[x], j = col[y];
        if (j < n_dense_) {
          if (i >= j) dense_(i, j) += wx * val[y];  // lower part of the dense columns
        } else if (i >= n_dense_) {
          AddTexelPair(i - n_dense_, j, wx * val[y]);
        }
      }
    }
  }

  Eigen::SparseMatrix<double> ToSparse() const {
    std::vector<Triplet> t;
    for (int j = 0; j < n_dense_; ++j) {
      for (int i = j; i < n_; ++i) {
        const double v = dense_(i, j);
        if (v == 0) continue;
        t.emplace_back(i, j, v);
        if (i != j) t.emplace_back(j, i, v);
      }
    }
    for (int a = 0; a < n_ - n_dense_; ++a) {
      for (int m = 0; m < nb_count_[a]; ++m) {
        const std::size_t s = static_cast<std::size_t>(a) * max_nb_ + m;
        t.emplace_back(n_dense_ + a, nb_col_[s], nb_val_[s]);
      }
    }
    Eigen::SparseMatrix<double> m(n_, n_);
    m.setFromTriplets(t.begin(), t.end());
    return m;
  }

 private:
  void AddTexelPair(int a, int col, double v) {
    const std::size_t base = static_cast<std::size_t>(a) * max_nb_;
    int& count = nb_count_[a];
    for (int m = 0; m < count; ++m) {
      if (nb_col_[base + m] == col) {
        nb_val_[base + m] += v;
        return;
      }
    }
    assert(count < max_nb_);  // bilinear footprints: a texel meets at most 9 texels
    nb_col_[base + count] = col;
    nb_val_[base + count] = v;
    ++count;
  }

  int n_, n_dense_, max_nb_;
  Eigen::MatrixXd dense_;
  std::vector<int> nb_count_;
  std::vector<int> nb_col_;
  std::vector<double> nb_val_;
};

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
  if (options.param == FactorParam::kHalfDiff && options.resolution > kMaxHalfDiffResolution) {
    throw InputError(
        fmt::format("resolution {} too large for halfdiff (at most {}: the q "
                    "texture is solved texel by texel)",
                    options.resolution, kMaxHalfDiffResolution));
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
  s->n_p_ = NumP(n);
  s->n_q_ = NumQ(options.param, n);
  const int n_p = s->n_p_;

  // ---- data rows, accumulated into M as they are made ----
  // Per-axis caches: the row of a cell depends on (theta_h) and (theta_d, phi_d) separately,
  // and its directions only through cos theta_i, cos theta_o at the cell centre:
  //   wi = R_y(theta_h) d, d = (sin td cos pd, sin td sin pd, cos td), wo = 2 (wi.h) h - wi
  //   => cos theta_i = cos th cos td - sin th sin td cos pd,
  //      cos theta_o = cos th cos td + sin th sin td cos pd        (geometry.h FromHalfDiff).
  const int nh = grid.n_theta_h, nd = grid.n_theta_d, np = grid.n_phi_d;
  std::vector<double> cth(nh), sth(nh), ctd(nd), std_(nd), cpd(np);
  std::vector<Linear2> h_knots(nh);  // sqrt-theta profile of theta_h
  for (int i = 0; i < nh; ++i) {
    const double th = grid.ThetaHAt(i + 0.5);
    cth[i] = std::cos(th);
    sth[i] = std::sin(th);
    h_knots[i] = ProfileWeights(DiskRadius(FactorMap::kDiskSqrtTheta, th), k);
  }
  for (int i = 0; i < nd; ++i) {
    const double td = grid.ThetaDAt(i + 0.5);
    ctd[i] = std::cos(td);
    std_[i] = std::sin(td);
  }
  for (int i = 0; i < np; ++i) cpd[i] = std::cos(grid.PhiDAt(i + 0.5));
  std::vector<Bilinear> dphi_texels;  // halfdiff: q lookup of (theta_d, phi_d)
  if (!mccool) {
    dphi_texels.resize(static_cast<std::size_t>(nd) * np);
    for (int id = 0; id < nd; ++id) {
      for (int ip = 0; ip < np; ++ip) {
        dphi_texels[static_cast<std::size_t>(id) * np + ip] =
            ThetaDPhiDLookup(grid.ThetaDAt(id + 0.5), grid.PhiDAt(ip + 0.5), n, n);
      }
    }
  }
  // Parabolic radius tan(theta / 2) = sqrt((1 - cos) / (1 + cos)).
  auto parabolic = [k](double c) {
    return ProfileWeights(std::sqrt(std::max(0.0, (1 - c) / (1 + c))), k);
  };
  const double cos_max = std::cos(options.max_theta);
  NormalAccumulator acc(s->n_p_ + s->n_q_, mccool ? s->n_p_ + s->n_q_ : n_p, 9);

  const std::size_t max_rows =
      static_cast<std::size_t>(std::count_if(mask.begin(), mask.end(), [](auto m) { return m; }));
  s->row_start_.reserve(max_rows + 1);
  s->row_cells_.reserve(max_rows);
  s->row_weight_.reserve(max_rows);
  s->col_.reserve(6 * max_rows);
  s->val_.reserve(6 * max_rows);
  s->row_start_.push_back(0);
  double weight_sum = 0;
  for (int ih = 0; ih < nh; ++ih) {
    for (int id = 0; id < nd; ++id) {
      const double w = options.weighting == FactorWeighting::kSolidAngle
                           ? CellSolidAngleWeight(grid, ih, id)
                           : 1.0 / static_cast<double>(grid.NumCells());
      const double a = cth[ih] * ctd[id], b = sth[ih] * std_[id];
      for (int ip = 0; ip < np; ++ip) {
        const std::size_t idx = grid.Index(ih, id, ip);
        if (!mask[idx]) continue;
        const double cos_i = a - b * cpd[ip], cos_o = a + b * cpd[ip];
        if (!(cos_i > 0 && cos_o > 0) || cos_i < cos_max || cos_o < cos_max) continue;
        RowEntries e;
        const Linear2& lh = h_knots[ih];
        if (mccool) {
          // log f = log p(wi) + log q(wh) + log p(wo); each factor radial (factor_param.h).
          for (double c : {cos_i, cos_o}) {
            const Linear2 l = parabolic(c);
            e.Add(l.index[0], l.weight[0]);
            e.Add(l.index[1], l.weight[1]);
          }
          e.Add(n_p + lh.index[0], lh.weight[0]);
          e.Add(n_p + lh.index[1], lh.weight[1]);
        } else {
          // log f = log p(wh) + log q(theta_d, phi_d).
          e.Add(lh.index[0], lh.weight[0]);
          e.Add(lh.index[1], lh.weight[1]);
          const Bilinear& q = dphi_texels[static_cast<std::size_t>(id) * np + ip];
          for (int c = 0; c < 4; ++c) e.Add(n_p + q.index[c], q.weight[c]);
        }
        e.Sort();
        for (int c = 0; c < e.n; ++c) {
          // Rounded to the stored float32 before M is assembled: M = A^T W A + S^T S holds
          // exactly for the A that Solve and the refinement read.
          e.val[c] = static_cast<float>(e.val[c]);
          s->col_.push_back(e.col[c]);
          s->val_.push_back(static_cast<float>(e.val[c]));
        }
        acc.Add(e.col.data(), e.val.data(), e.n, w);
        s->row_start_.push_back(static_cast<int>(s->col_.size()));
        s->row_cells_.push_back(static_cast<std::uint32_t>(idx));
        s->row_weight_.push_back(w);
        weight_sum += w;
      }
    }
  }
  const std::size_t rows = s->row_cells_.size();
  if (rows == 0 || !(weight_sum > 0)) {
    throw InputError(
        "no usable cell (every cell is masked, below the horizon or beyond the "
        "angle cut-off)");
  }

  // ---- normal matrix M = A^T W A + L^T L + g g^T ----
  const int n_unknowns = s->n_p_ + s->n_q_;
  const Eigen::SparseMatrix<double> normal = acc.ToSparse();

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
  s->smooth_ = std::move(l);
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

void FactorSystem::ApplyReduced(const Eigen::MatrixX3d& v,
                                const std::vector<std::uint32_t>& removed,
                                Eigen::MatrixX3d* out) const {
  *out = normal_ * v;
  for (std::uint32_t r : removed) {
    Eigen::RowVector3d dot = Eigen::RowVector3d::Zero();
    for (int e = row_start_[r]; e < row_start_[r + 1]; ++e) dot += val_[e] * v.row(col_[e]);
    dot *= row_weight_[r];
    for (int e = row_start_[r]; e < row_start_[r + 1]; ++e) out->row(col_[e]) -= val_[e] * dot;
  }
}

bool FactorSystem::Solve(const RowValues& y, const std::vector<std::uint32_t>& removed,
                         Eigen::MatrixX3d* x, FactorSolveInfo* info) const {
  const std::size_t rows = row_cells_.size();
  assert(static_cast<std::size_t>(y.rows()) == rows);
  if (removed.size() > kMaxRemovedRows) return false;
  const int n = n_p_ + n_q_;
  // b = A^T W y over the kept rows.
  Eigen::MatrixX3d b = Eigen::MatrixX3d::Zero(n, 3);
  double ywy = 0, wsum = 0;  // y^T W y and sum of w over the kept rows (all channels)
  std::size_t next_removed = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    if (next_removed < removed.size() && removed[next_removed] == r) {
      ++next_removed;
      continue;
    }
    const double w = row_weight_[r];
    const double* yr = y.data() + 3 * r;
    const double y0 = w * yr[0], y1 = w * yr[1], y2 = w * yr[2];
    ywy += y0 * yr[0] + y1 * yr[1] + y2 * yr[2];
    wsum += 3 * w;
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
    // at most |removed| + 1 steps; clustered spectra make it far fewer in practice. The three
    // channels run as independent CGs whose matrix products and triangular solves are batched
    // (one pass over M and the factor serves all three).
    Eigen::MatrixX3d r, z, p, ap;
    ApplyReduced(sol, removed, &ap);
    r = b - ap;
    z = ldlt_.solve(r);
    p = z;
    Eigen::Array3d rz = (r.array() * z.array()).colwise().sum().transpose();
    const Eigen::Array3d tol = 1e-11 * b.colwise().norm().transpose().array().max(1e-300);
    auto converged = [&] { return (r.colwise().norm().transpose().array() <= tol).all(); };
    int it = 0;
    for (; it < kMaxPcgIterations && !converged(); ++it) {
      ApplyReduced(p, removed, &ap);
      const Eigen::Array3d pap = (p.array() * ap.array()).colwise().sum().transpose();
      for (int c = 0; c < 3; ++c) {
        if (r.col(c).norm() <= tol[c]) continue;  // this channel is done: freeze it
        if (!(pap[c] > 0)) return false;
        const double alpha = rz[c] / pap[c];
        sol.col(c) += alpha * p.col(c);
        r.col(c) -= alpha * ap.col(c);
      }
      z = ldlt_.solve(r);
      for (int c = 0; c < 3; ++c) {
        const double rz_new = r.col(c).dot(z.col(c));
        p.col(c) = z.col(c) + (rz[c] > 0 ? rz_new / rz[c] : 0.0) * p.col(c);
        rz[c] = rz_new;
      }
    }
    if (!converged()) return false;
    local.pcg_iterations = it;
  }
  if (!sol.allFinite()) return false;
  const double sq = ywy - (sol.array() * b.array()).sum() - (smooth_ * sol).squaredNorm();
  local.weighted_rms = wsum > 0 ? std::sqrt(std::max(0.0, sq) / wsum) : 0.0;
  *x = sol;
  if (info) *info = local;
  return true;
}

double FactorSystem::WeightedRms(const RowValues& y, const std::vector<std::uint32_t>& removed,
                                 const Eigen::MatrixX3d& x) const {
  const Eigen::Index n = x.rows();
  double sum = 0, wsum = 0;
  std::size_t next_removed = 0;
  for (std::size_t r = 0; r < row_cells_.size(); ++r) {
    if (next_removed < removed.size() && removed[next_removed] == r) {
      ++next_removed;
      continue;
    }
    double p0 = 0, p1 = 0, p2 = 0;
    for (int e = row_start_[r]; e < row_start_[r + 1]; ++e) {
      const double a = val_[e];
      const double* xp = x.data() + col_[e];
      p0 += a * xp[0];
      p1 += a * xp[n];
      p2 += a * xp[2 * n];
    }
    const double* yr = y.data() + 3 * r;
    const double d0 = yr[0] - p0, d1 = yr[1] - p1, d2 = yr[2] - p2;
    sum += row_weight_[r] * (d0 * d0 + d1 * d1 + d2 * d2);
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
