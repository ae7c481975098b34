#include "report/report_slices.h"

#include <fmt/core.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "models/registry.h"

namespace brdfit::report {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDeg = 180.0 / kPi;

// Mean of the channels if all are finite and the mean is positive (log axes), else NaN.
double Gray(const double rgb[3]) {
  const double g = (rgb[0] + rgb[1] + rgb[2]) / 3.0;
  const bool finite = std::isfinite(rgb[0]) && std::isfinite(rgb[1]) && std::isfinite(rgb[2]);
  return finite && g > 0 ? g : kNaN;
}
}  // namespace

std::vector<double> DefaultSliceThetaD() { return {0.0, 30.0, 60.0, 75.0}; }

std::vector<Slice> ComputeThetaHSlices(const Table& table, const std::vector<double>& theta_d_deg,
                                       double phi_d_deg,
                                       const std::vector<NamedPredictor>& predictors) {
  const Grid& g = table.grid;
  std::vector<Slice> slices;
  for (const double td : theta_d_deg) {
    const HalfDiffAngles probe{0.0, td / kDeg, phi_d_deg / kDeg};
    int ih0 = 0, id = 0, ip = 0;
    g.Unindex(g.CellOf(probe), &ih0, &id, &ip);
    Slice s;
    const HalfDiffAngles c0 = g.CellCentre(0, id, ip);
    s.theta_d_deg = c0.theta_d * kDeg;
    s.phi_d_deg = c0.phi_d * kDeg;
    s.series.push_back({"measured", "measured", {}});
    for (const auto& p : predictors) s.series.push_back({p.label, p.role, {}});
    for (int ih = 0; ih < g.n_theta_h; ++ih) {
      const std::size_t idx = g.Index(ih, id, ip);
      const HalfDiffAngles a = g.CellCentre(ih, id, ip);
      s.theta_h_deg.push_back(a.theta_h * kDeg);
      const bool above = g.CellAboveHorizon(idx);
      s.series[0].value.push_back(above && table.valid[idx] ? Gray(table.Value(idx)) : kNaN);
      for (std::size_t k = 0; k < predictors.size(); ++k) {
        double v = kNaN;
        if (above) {
          const std::array<double, 3> f = predictors[k].predict(a);
          v = Gray(f.data());
        }
        s.series[k + 1].value.push_back(v);
      }
    }
    slices.push_back(std::move(s));
  }
  return slices;
}

Predictor ModelPredictor(const std::string& model, const std::vector<double>& params) {
  const ModelInfo* m = FindModel(model);
  if (!m) throw InputError("unknown model '" + model + "'; known models: " + ModelNames());
  if (params.size() != m->params.size()) {
    throw InputError(fmt::format("model {} has {} parameters, the result gives {}", model,
                                 m->params.size(), params.size()));
  }
  return [m, params](const HalfDiffAngles& a) {
    std::array<double, 3> rgb{};
    m->eval(params.data(), MakeGeometry(a), rgb.data());
    return rgb;
  };
}

}  // namespace brdfit::report
