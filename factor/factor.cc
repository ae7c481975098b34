#include "factor/factor.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/core.h>

#include "core/error.h"
#include "factor/factor_refine.h"

namespace brdfit {
namespace {

// y = ln f per row; rows with a channel <= 0 or not finite are listed in *removed (y = 0).
void LogValues(const Table& table, const FactorSystem& sys, RowValues* y,
               std::vector<std::uint32_t>* removed) {
  const auto& cells = sys.row_cells();
  y->resize(static_cast<Eigen::Index>(cells.size()), 3);
  removed->clear();
  for (std::size_t r = 0; r < cells.size(); ++r) {
    const double* v = table.Value(cells[r]);
    const bool ok = v[0] > 0 && v[1] > 0 && v[2] > 0 && std::isfinite(v[0]) &&
                    std::isfinite(v[1]) && std::isfinite(v[2]);
    if (!ok) {
      removed->push_back(static_cast<std::uint32_t>(r));
      y->row(r).setZero();
      continue;
    }
    for (int c = 0; c < 3; ++c) (*y)(r, c) = std::log(v[c]);
  }
}

float ToTexel(double log_value, std::size_t* clamped) {
  constexpr double kMax = std::numeric_limits<float>::max();
  constexpr double kMin = std::numeric_limits<float>::min();  // smallest normal
  double v = std::exp(log_value);
  if (!(v <= kMax)) {
    v = kMax;
    ++*clamped;
  } else if (v < kMin) {
    v = kMin;
    ++*clamped;
  }
  return static_cast<float>(v);
}

// A radial profile (k knots over rho in [0, 1] of `map`) baked into an n x n disk texture.
RgbImage BakeDisk(const Eigen::MatrixX3d& x, int offset, int k, int n, std::size_t* clamped) {
  RgbImage img = RgbImage::Filled(n, n, 0.0f);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double rho =
          std::min(1.0, std::hypot(DiskTexelCentre(i, n), DiskTexelCentre(j, n)));  // corners: rim
      const Linear2 l = ProfileWeights(rho, k);
      float* t = img.At(i, j);
      for (int c = 0; c < 3; ++c) {
        t[c] = ToTexel(
            l.weight[0] * x(offset + l.index[0], c) + l.weight[1] * x(offset + l.index[1], c),
            clamped);
      }
    }
  }
  return img;
}

// Texel-valued unknowns (row-major n x n) into a texture.
RgbImage BakeTexels(const Eigen::MatrixX3d& x, int offset, int n, std::size_t* clamped) {
  RgbImage img = RgbImage::Filled(n, n, 0.0f);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      float* t = img.At(i, j);
      for (int c = 0; c < 3; ++c) t[c] = ToTexel(x(offset + j * n + i, c), clamped);
    }
  }
  return img;
}

}  // namespace

Factorization Factor(const Table& table, const FactorOptions& options, FactorSystemCache* cache) {
  const auto t0 = std::chrono::steady_clock::now();
  if (options.rank < 1 || options.rank > kMaxFactorRank) {
    throw InputError(fmt::format("rank must be in [1, {}] (got {})", kMaxFactorRank, options.rank));
  }
  if (options.refine_iterations < 1 || options.refine_rows < 1) {
    throw InputError("refinement needs at least one iteration and one row");
  }
  FactorSystemCache local(1);
  if (!cache) cache = &local;
  Factorization out;
  out.options = options;
  FactorStats& st = out.stats;
  st.grid_cells = table.grid.NumCells();
  st.valid_cells = table.CountValid();

  bool hit = false;
  auto sys = cache->GetOrBuild(table.grid, table.valid, options, &hit);
  st.system_reused = hit;
  if (!hit) st.system_seconds = sys->build_seconds();
  st.usable_cells = sys->num_rows();

  RowValues y;
  Eigen::MatrixX3d x;
  std::vector<std::uint32_t> removed;
  LogValues(table, *sys, &y, &removed);
  st.nonpositive_cells = removed.size();
  if (removed.size() == sys->num_rows()) {
    throw InputError("every usable cell has a channel <= 0: nothing to factor in log space");
  }
  FactorSolveInfo info;
  if (sys->Solve(y, removed, &x, &info)) {
    st.pcg_iterations = info.pcg_iterations;
  } else {
    // Too many cells to drop by a low-rank correction: a system for the reduced mask (cached
    // too, so materials with the same zero cells reuse it).
    std::vector<std::uint8_t> reduced = table.valid;
    for (std::uint32_t r : removed) reduced[sys->row_cells()[r]] = 0;
    sys = cache->GetOrBuild(table.grid, reduced, options, &hit);
    st.system_rebuilt = true;
    if (!hit) st.system_seconds += sys->build_seconds();
    LogValues(table, *sys, &y, &removed);
    if (!removed.empty() || !sys->Solve(y, removed, &x, &info)) {
      throw std::runtime_error("factorization solve failed (non-finite solution)");
    }
  }
  st.used_cells = sys->num_rows() - removed.size();
  st.solve_log_rms = info.weighted_rms;

  const int n = options.resolution;
  const int k = sys->num_p();
  auto bake = [&](const Eigen::MatrixX3d& xt, std::size_t* clamped) {
    FactorTerm t;
    t.p = BakeDisk(xt, 0, k, n, clamped);
    t.q = options.param == FactorParam::kMcCool ? BakeDisk(xt, k, sys->num_q(), n, clamped)
                                                : BakeTexels(xt, k, n, clamped);
    return t;
  };
  if (!options.NeedsRefinement()) {
    out.brdf = FactoredBrdf(options.param, {0, 0, 0}, {bake(x, &st.clamped_texels)});
  } else {
    const auto t1 = std::chrono::steady_clock::now();
    RefineOptions ro;
    ro.loss = options.refine_loss;
    ro.diffuse = options.diffuse;
    ro.rank = options.rank;
    ro.max_iterations = options.refine_iterations;
    ro.max_rows = options.refine_rows;
    const RefineResult r = RefineFactorization(*sys, table, x, removed, ro);
    std::vector<FactorTerm> terms;
    for (const auto& xt : r.terms) terms.push_back(bake(xt, &st.clamped_texels));
    out.brdf = FactoredBrdf(options.param, r.diffuse, std::move(terms));
    for (const RefineResult::Stage& stage : r.lower_ranks) {
      std::vector<FactorTerm> lower;
      std::size_t unreported = 0;  // the stats describe the result, not the stages
      for (const auto& xt : stage.terms) lower.push_back(bake(xt, &unreported));
      out.lower_ranks.emplace_back(options.param, stage.diffuse, std::move(lower));
    }
    st.refine_rows = r.rows;
    st.refine_iterations = r.iterations;
    st.refine_rel_rms_start = r.rel_rms_start;
    st.refine_rel_rms = r.rel_rms;
    st.refine_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  }
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace brdfit
