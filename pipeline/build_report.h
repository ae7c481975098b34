// The report `brdfit report` writes, as data (report/report_model.h): the results its inputs
// hold (read by report::ReadReportInputs), and beside each material whose table is at hand its
// θh slices (report/report_slices.h) and the renders of the rendered metric's scene
// (pipeline/rendered_views.h). The command reads, calls this, renders the page
// (report/html_report.h) and prints.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "report/report_model.h"

namespace brdfit::pipeline {

struct ReportRequest {
  std::string title;                // empty: the report's default
  std::vector<double> theta_d;      // the slices' θd (degrees)
  double phi_d = 90;                // and φd
  bool slices = true;
  bool renders = true;
  std::vector<double> render_lights;  // degrees from the view (CheckViewLights)
  // Without it the first unreadable table ends the build (InputError); with it, each becomes a
  // note on the page and an entry of BuiltReport::problems.
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

// From the sources read with `unreadable` (the inputs left out with keep_going, each noted on
// the page). Throws InputError naming the file (without keep_going) or when there is nothing
// to report.
BuiltReport BuildReport(report::ReportSources sources, std::vector<std::string> unreadable,
                        const ReportRequest& request);

}  // namespace brdfit::pipeline
