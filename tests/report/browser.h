// Headless Chromium (Debian's `chromium`) for the report tests: loads a page from a file with
// no network, no profile and a timeout, and reads what the page recorded about itself
// (report/html_report.h: data-charts-expected, data-charts-rendered, data-errors on <body>) plus
// every console message Chromium logged. Also takes screenshots.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace brdfit::testing {

// $BRDFIT_CHROMIUM, else chromium on PATH (/usr/bin/chromium); empty if neither exists.
std::string FindChromium();

struct PageCheck {
  int exit_code = -1;                 // of the browser process (124: timed out)
  std::string dom;                    // the DOM after the page's scripts ran
  bool has_body_marker = false;       // <body data-charts-expected=...> found
  int charts_expected = -1, charts_rendered = -1;
  int canvases_marked_rendered = 0;   // <canvas ... data-rendered="1">
  int wide_tables = -1;               // <body data-wide-tables>: tables wider than the page
  std::vector<std::string> page_errors;     // <body data-errors> (window.__errors)
  std::vector<std::string> console_lines;   // Chromium's CONSOLE log lines (any level)
  std::string log;                          // Chromium's stderr, for failure messages
};

// Loads `html` (a local file) in a fresh profile under `work_dir`, in a window `width` pixels
// wide (0: Chromium's default); waits for scripts up to a virtual-time budget; kills the browser
// after `timeout_s` seconds.
PageCheck LoadPage(const std::filesystem::path& html, const std::filesystem::path& work_dir,
                   int timeout_s = 120, int width = 0);

// Screenshot of the top `height` pixels of the page at `width`. Returns the browser's exit code.
int Screenshot(const std::filesystem::path& html, const std::filesystem::path& png,
               const std::filesystem::path& work_dir, int width, int height, int timeout_s = 120);

struct InkStats {
  int width = 0, height = 0;
  double non_white_fraction = 0;  // pixels whose RGB differs from white by more than 8/255
  int distinct_colors = 0;        // distinct RGB values quantized to 5 bits per channel
};
InkStats MeasureInk(const std::filesystem::path& png);

}  // namespace brdfit::testing
