// One self-contained HTML file from a report (report/report_model.h): tables of every
// approximation's metrics, parameters and times with the best highlighted, Pareto plots of run
// time against error, θh slices, metric bars, and the preview renders as data: URIs. The plots
// are drawn by Chart.js, read at generation time from Debian's libjs-chart.js and inlined, so
// the page opens offline.
//
// The page reports on itself for tests and users: <body data-charts-expected="N"
// data-charts-rendered="K" data-errors="[...]"> once its scripts ran (K counts charts whose
// canvas holds drawn pixels); window.__errors collects uncaught errors and console.error calls,
// which are also shown at the top of the page.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "report/report_model.h"

namespace brdfit::report {

inline constexpr const char* kDefaultChartJs = "/usr/share/javascript/chart.js/chart.min.js";

// $BRDFIT_CHART_JS if set, else kDefaultChartJs.
std::filesystem::path ChartJsPath();

// Reads Chart.js. Throws InputError naming the path, with the fix (install libjs-chart.js or
// set BRDFIT_CHART_JS), if it is missing or does not look like Chart.js.
std::string ReadChartJs(const std::filesystem::path& path = ChartJsPath());

// The whole page. `chart_js` is the library's source text. Render PNGs that cannot be read are
// replaced by a note naming the file.
std::string RenderHtml(const Report& report, const std::string& chart_js);

// RenderHtml + WriteTextAtomically.
void WriteHtmlReport(const std::filesystem::path& out, const Report& report,
                     const std::filesystem::path& chart_js = ChartJsPath());

// Helpers, exposed for tests.
std::string HtmlEscape(std::string_view text);
std::string Base64(std::string_view bytes);  // RFC 4648 §4, with padding
// JSON text made safe inside <script>: every '<' (only ever inside strings) becomes \u003c,
// the same JSON value.
std::string ScriptSafeJson(const std::string& json_text);

}  // namespace brdfit::report
