// The report `brdfit report` writes, as data (report/report_model.h): the results read from
// the inputs (report/report_inputs.h), and beside each material whose table is at hand its θh
// slices (report/report_slices.h) and the renders of the rendered metric's scene
// (pipeline/rendered_views.h). The command renders the page (report/html_report.h) and prints.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "report/report_model.h"

namespace brdfit::pipeline {

struct ReportRequest {
  std::vector<std::string> inputs;  // expanded (pipeline/inputs.h ExpandInputs)
  std::string title;                // empty: the report's default
  std::vector<double> theta_d;      // the slices' θd (degrees)
  double phi_d = 90;                // and φd
  bool slices = true;
  bool renders = true;
  std::vector<double> render_lights;  // degrees from the view (CheckViewLights)
  // Without it the first unreadable input or table ends the build (InputError); with it, each
  // becomes a note on the page and an entry of BuiltReport::problems.
  bool keep_going = false;
  // Called as each material's slices and renders start (a progress bar), and with each warning
  // (a table the results name that is missing: the page says so, the user should see it).
  std::function<void(std::size_t materials, const std::string& material)> on_material;
  std::function<void(const std::string& material, const std::string& warning)> on_warning;
};

struct BuiltReport {
  report::Report report;
  std::vector<std::string> problems;  // with keep_going: what could not be read
};

// Slices of one material draw at most this many of its results: the pick, then by
// report::RankEntries (a material with thousands of fits would draw thousands of lines).
inline constexpr std::size_t kMaxSliceResults = 8;

// Throws InputError naming the file (without keep_going) or when there is nothing to report.
BuiltReport BuildReport(const ReportRequest& request);

}  // namespace brdfit::pipeline
