#include "core/nbrdf_network.h"

#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <thread>

#include "core/error.h"
#include "core/nbrdf_forward.h"

namespace brdfit {

std::array<double, 3> EvalNbrdf(const NbrdfNetwork& net, const HalfDiffAngles& a) {
  Eigen::RowVectorXd x(6);
  x << std::sin(a.theta_h), 0.0, std::cos(a.theta_h), std::sin(a.theta_d) * std::cos(a.phi_d),
      std::sin(a.theta_d) * std::sin(a.phi_d), std::cos(a.theta_d);
  const Eigen::RowVectorXd h1 = (x * net.k1 + net.b1).cwiseMax(0.0);
  const Eigen::RowVectorXd h2 = (h1 * net.k2 + net.b2).cwiseMax(0.0);
  const Eigen::RowVectorXd y = h2 * net.k3 + net.b3;
  return {std::expm1(y[0]), std::expm1(y[1]), std::expm1(y[2])};
}

NbrdfTabulation TabulateNbrdf(const NbrdfNetwork& net, const Grid& grid, int threads) {
  NbrdfTabulation out;
  out.table = Table::Empty(grid);
  Table& t = out.table;
  const int nd = grid.n_theta_d, np = grid.n_phi_d;
  const Eigen::Index rows = static_cast<Eigen::Index>(nd) * np;

  // The difference-vector part of x is the same in every theta_h slice: fold it into the first
  // layer once. P = [sin td cos pd, sin td sin pd, cos td] K1[3:6] + b1, one row per (id, ip).
  Eigen::MatrixXd dvec(rows, 3);
  Eigen::VectorXd cos_pd(rows), sin_td_row(rows), cos_td_row(rows);
  for (int id = 0; id < nd; ++id) {
    const double td = grid.ThetaDAt(id + 0.5);
    for (int ip = 0; ip < np; ++ip) {
      const double pd = grid.PhiDAt(ip + 0.5);
      const Eigen::Index r = static_cast<Eigen::Index>(id) * np + ip;
      dvec.row(r) << std::sin(td) * std::cos(pd), std::sin(td) * std::sin(pd), std::cos(td);
      cos_pd[r] = std::cos(pd);
      sin_td_row[r] = std::sin(td);
      cos_td_row[r] = std::cos(td);
    }
  }
  const Eigen::MatrixXd p = (dvec * net.k1.bottomRows(3)).rowwise() + net.b1;
  // The hidden layers four cells at a time with AVX2 + FMA where the CPU has them
  // (io/nbrdf_forward.h: the same values to ~1e-15 relative, not the same bits), else Eigen.
  const bool vectorized = NbrdfForwardVectorized();

  struct Counts {
    std::size_t below = 0, clamped_values = 0, clamped_cells = 0;
    bool non_finite = false;
    std::size_t non_finite_cell = 0;
  };
  auto slice = [&](int ih, Counts& cnt, std::vector<Eigen::Index>& above) {
    const double th = grid.ThetaHAt(ih + 0.5);
    const double sh = std::sin(th), ch = std::cos(th);
    // Only the cells above the horizon go through the network (a quarter of the MERL grid is
    // below it). Directions at the cell centre with phi_h = 0 (geometry.h FromHalfDiff):
    // wi.z = cos th cos td - sin th sin td cos pd, wo.z = cos th cos td + sin th sin td cos pd.
    above.clear();
    for (Eigen::Index r = 0; r < rows; ++r) {
      const double a = ch * cos_td_row[r], b = sh * sin_td_row[r] * cos_pd[r];
      if (a - b > 0 && a + b > 0) {
        above.push_back(r);
      } else {
        ++cnt.below;  // masked (valid stays 0, value 0)
      }
    }
    if (above.empty()) return;
    // x = (sin th, 0, cos th, d): the half-vector part adds one row vector to P. Fewer rows can
    // send some of them through Eigen's GEMM remainder path, which sums in another order: a
    // few values per table change in the last bits (<= 1.4e-13 relative, docs/fitting.md).
    const Eigen::RowVectorXd hpart = sh * net.k1.row(0) + ch * net.k1.row(2);
    // y(i, c): the network's log-space output of cell above[i].
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> y(above.size(), 3);
    if (vectorized) {
      NbrdfForwardArgs args;
      args.p = p.data();
      args.p_rows = static_cast<std::size_t>(p.rows());
      args.rows = above.data();
      args.n = above.size();
      args.hpart = hpart.data();
      args.k2 = net.k2.data();
      args.b2 = net.b2.data();
      args.k3 = net.k3.data();
      args.b3 = net.b3.data();
      args.h1 = static_cast<int>(net.k2.rows());
      args.h2 = static_cast<int>(net.k2.cols());
      NbrdfForwardAvx2(args, y.data());
    } else {
      const Eigen::MatrixXd h1 = (p(above, Eigen::all).rowwise() + hpart).cwiseMax(0.0);
      const Eigen::MatrixXd h2 = ((h1 * net.k2).rowwise() + net.b2).cwiseMax(0.0);
      y = (h2 * net.k3).rowwise() + net.b3;
    }
    const std::size_t base = grid.Index(ih, 0, 0);
    for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(above.size()); ++i) {
      const std::size_t idx = base + static_cast<std::size_t>(above[i]);
      bool clamped = false;
      for (int c = 0; c < 3; ++c) {
        double f = std::expm1(y(i, c));
        if (!std::isfinite(f) && !cnt.non_finite) {
          cnt.non_finite = true;
          cnt.non_finite_cell = idx;
        }
        if (f < 0) {
          f = 0;  // README: clamp negative outputs to 0 (counted)
          ++cnt.clamped_values;
          clamped = true;
        }
        t.rgb[3 * idx + c] = f;
      }
      cnt.clamped_cells += clamped;
      t.valid[idx] = 1;
    }
  };

  const int n_threads = std::clamp(threads, 1, grid.n_theta_h);
  std::vector<Counts> counts(n_threads);
  if (n_threads == 1) {
    std::vector<Eigen::Index> above;
    for (int ih = 0; ih < grid.n_theta_h; ++ih) slice(ih, counts[0], above);
  } else {
    std::vector<std::thread> pool;
    for (int k = 0; k < n_threads; ++k) {
      pool.emplace_back([&, k] {
        std::vector<Eigen::Index> above;
        for (int ih = k; ih < grid.n_theta_h; ih += n_threads) slice(ih, counts[k], above);
      });
    }
    for (auto& th : pool) th.join();
  }
  for (const Counts& c : counts) {
    if (c.non_finite) {
      throw InputError(net.source,
                       fmt::format("network output is not finite at cell {}", c.non_finite_cell));
    }
    out.below_horizon += c.below;
    out.clamped_values += c.clamped_values;
    out.clamped_cells += c.clamped_cells;
  }
  t.provenance.source = net.source;
  t.provenance.generator = "nbrdf";
  t.provenance.model = "nbrdf";
  nlohmann::ordered_json params;
  params["material"] = net.material;
  params["clamped_values"] = out.clamped_values;
  t.provenance.parameters_json = params.dump();
  return out;
}

}  // namespace brdfit
