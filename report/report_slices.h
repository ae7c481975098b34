// θh slices for reports: at a few fixed θd (and φd = 90°), the measured cells of a table
// against what each approximation predicts at the same cell centres (the points the fit
// metrics score; docs/conventions.md). Values are the mean of the three channels of f_r
// (1/sr, without the cosine); cells below the horizon at their centre, invalid cells and
// non-positive or non-finite values are NaN (drawn as gaps on a log axis).
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "report/report_model.h"
#include "core/table.h"
#include "models/geometry.h"

namespace brdfit::report {

// f_r (1/sr, linear RGB, without the cosine) at half/difference angles.
using Predictor = std::function<std::array<double, 3>(const HalfDiffAngles&)>;

struct NamedPredictor {
  std::string label;  // legend entry, e.g. "lambert+ggx" or "factor:mccool"
  std::string role;   // "fitted" or "factored"
  Predictor predict;
};

// Default θd of the slices (degrees); each is replaced by the centre of the bin holding it.
std::vector<double> DefaultSliceThetaD();

// One slice per θd, over every θh bin of the table's grid, at the φd bin holding phi_d_deg.
std::vector<Slice> ComputeThetaHSlices(const Table& table, const std::vector<double>& theta_d_deg,
                                       double phi_d_deg,
                                       const std::vector<NamedPredictor>& predictors);

// A predictor from a registered model and its fitted parameters (models/registry.h). Throws
// InputError if the model is unknown or the parameter count does not match.
Predictor ModelPredictor(const std::string& model, const std::vector<double>& params);

}  // namespace brdfit::report
