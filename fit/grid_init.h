// The initializer: a grid over the shape parameters; at each grid point the linear colour
// weights are solved by box-constrained weighted least squares (variable projection, Golub &
// Pereyra 1973). The grid spans the log-scale shape parameters (alpha, exponents); linear-scale
// ones (cxy, f0, metallic) get a short adaptive compass search from their defaults at each grid
// point (first step 1/64 of the range, doubled on success: defaults are usually good and ranges
// can be wide). The best points are refined by a compass search over all shape parameters (same
// inner solve).
//
// The weighted least squares is the loss linearized at the data: e ~ d (f - m) with
// d = inv T'(m c) c, so each cell/channel weighs omega d^2 with target m. Every grid point is
// scored with the true loss (robust function included). The best points get two Gauss-Newton
// refinements of their weights (relinearized at the current prediction) and are rescored.
// Assumes what ParamRole promises: channel c of the model is jointly linear in the channel-c
// weights of all lobes (tested for every catalog model); a part no weight scales (ue4) is
// evaluated separately and kept as an offset.
#pragma once

#include <ceres/loss_function.h>

#include <cstddef>
#include <vector>

#include "fit/loss.h"
#include "fit/param_layout.h"
#include "fit/samples.h"

namespace brdfit::internal {

struct InitCandidate {
  std::vector<double> params;  // parameter space (not log)
  double cost = 0;
};

// f_r of a model at a geometry, double precision (models/param.h: M::Eval<double>).
using EvalFn = void (*)(const double* params, const Geometry& g, double rgb[3]);

// A component at n geometries: rgb[s * stride + ch] for s < n, its EvalFn's values bit for bit
// without a call through a pointer per sample (a basis column of the initializer).
using EvalColumnFn = void (*)(const double* params, const Geometry* g, std::size_t n, double* rgb,
                              std::size_t stride);

// One lobe of a sum (models/sum.h: its own Eval at its slice [offset, offset + count) of the
// parameter vector), or the whole model for a model that is not a sum.
struct ComponentOps {
  EvalFn eval;
  std::size_t offset, count;
  EvalColumnFn column = nullptr;  // null: eval per sample
};

// Starting points over some shape parameters (indices dims; values in parameter space),
// uniform in the optimization space (log for log_scale parameters) over the bounds: a product
// grid in 1-D (48 points: alpha ratio 1.22 over [1e-4, 1]) and 2-D (14 x 14), Halton points
// beyond (343); coarse: 24, 8 x 8, 64. spacing: typical distance between points per
// dimension, as a fraction of the range.
struct ShapeStarts {
  std::vector<std::vector<double>> points;
  std::vector<double> spacing;
};
ShapeStarts MakeShapeStarts(const ParamLayout& layout, const std::vector<int>& dims, bool coarse);

class GridInitializer {
 public:
  // components: the model's lobes (ModelOps::components), which partition its parameters: a
  // basis column is its own lobe's Eval alone, and a change of one lobe's shape recomputes only
  // that lobe's column.
  GridInitializer(const Samples& s, const LossData& l, const ParamLayout& layout,
                  const std::vector<ComponentOps>& components, const ceres::LossFunction* robust);

  // The best `keep` candidates, best first (costs may be NaN only if every point failed).
  std::vector<InitCandidate> Run(int keep);

 private:
  InitCandidate EvaluatePoint(std::vector<double> p);
  void PatternSearch(InitCandidate* c, const std::vector<int>& dims,
                     const std::vector<double>& initial_step, double shrink_to,
                     int max_evaluations);
  std::vector<double> Spacing(const std::vector<int>& dims,
                              const std::vector<double>& fractions) const;
  void ComputeBasis(const std::vector<double>& p);
  double Predict(const std::vector<double>& p, std::size_t s, int ch) const;
  void SolveWeights(const std::vector<double>& w, const std::vector<double>& y,
                    std::vector<double>* p) const;
  void Relinearize(std::vector<double>* p);
  double Score(const std::vector<double>& p) const;

  const Samples& s_;
  const LossData& l_;
  const ParamLayout& layout_;
  const std::vector<ComponentOps>& components_;
  const ceres::LossFunction* robust_;
  std::vector<double> w_data_, y_data_, basis_, offset_;
  // Per lobe: its component and the shape parameters its column depends on (its component's);
  // the weightless components (offset_) and their shape parameters; the parameters the basis
  // was last computed at.
  std::vector<std::size_t> lobe_component_;
  std::vector<std::vector<int>> lobe_shape_;
  std::vector<std::size_t> offset_components_;
  std::vector<int> offset_shape_;
  std::vector<double> basis_at_;
};

}  // namespace brdfit::internal
