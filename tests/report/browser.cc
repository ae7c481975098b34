#include "tests/report/browser.h"

#include <fmt/core.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <sys/wait.h>

#include "io/image_io.h"

namespace brdfit::testing {

namespace fs = std::filesystem;

namespace {

std::string ShellQuote(const std::string& s) {
  std::string q = "'";
  for (const char c : s) {
    if (c == '\'') {
      q += "'\\''";
    } else {
      q += c;
    }
  }
  q += '\'';
  return q;
}

std::string ReadFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string HtmlUnescape(const std::string& s) {
  static const std::pair<std::string, char> kEntities[] = {
      {"&quot;", '"'}, {"&#39;", '\''}, {"&lt;", '<'}, {"&gt;", '>'}, {"&amp;", '&'}};
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    bool replaced = false;
    if (s[i] == '&') {
      for (const auto& [entity, c] : kEntities) {
        if (s.compare(i, entity.size(), entity) == 0) {
          out += c;
          i += entity.size();
          replaced = true;
          break;
        }
      }
    }
    if (!replaced) out += s[i++];
  }
  return out;
}

// Runs chromium with the common flags plus `extra`; stdout and stderr into files in `dir`.
int RunChromium(const std::vector<std::string>& extra, const fs::path& dir, int timeout_s,
                const fs::path& out, const fs::path& err) {
  const std::string chromium = FindChromium();
  if (chromium.empty()) return 127;
  const fs::path profile = dir / "profile";
  fs::remove_all(profile);
  fs::create_directories(profile);
  // A fresh profile and HOME; no sandbox (tests run as root in CI); no GPU; nothing that talks
  // to the network, and every host name unresolvable so that a page fetching anything fails.
  std::vector<std::string> args = {"--headless",
                                   "--no-sandbox",
                                   "--disable-gpu",
                                   "--disable-dev-shm-usage",
                                   "--disable-quic",
                                   "--no-first-run",
                                   "--no-default-browser-check",
                                   "--disable-background-networking",
                                   "--disable-component-update",
                                   "--disable-sync",
                                   "--disable-extensions",
                                   "--host-resolver-rules=MAP * ~NOTFOUND",
                                   "--user-data-dir=" + profile.string(),
                                   "--enable-logging=stderr",
                                   "--v=0",
                                   "--virtual-time-budget=15000"};
  args.insert(args.end(), extra.begin(), extra.end());
  std::string cmd = fmt::format("HOME={0} XDG_CONFIG_HOME={0} XDG_CACHE_HOME={0} timeout -k 10 {1} {2}",
                                ShellQuote(profile.string()), timeout_s, ShellQuote(chromium));
  for (const auto& a : args) {
    cmd += ' ';
    cmd += ShellQuote(a);
  }
  cmd += fmt::format(" > {} 2> {} < /dev/null", ShellQuote(out.string()), ShellQuote(err.string()));
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

}  // namespace

std::string FindChromium() {
  if (const char* env = std::getenv("BRDFIT_CHROMIUM"); env && *env) return env;
  for (const char* p : {"/usr/bin/chromium", "/usr/local/bin/chromium"}) {
    std::error_code ec;
    if (fs::exists(p, ec)) return p;
  }
  return "";
}

PageCheck LoadPage(const fs::path& html, const fs::path& work_dir, int timeout_s, int width) {
  PageCheck r;
  fs::create_directories(work_dir);
  const fs::path out = work_dir / "dom.html", err = work_dir / "chromium.log";
  std::vector<std::string> args = {"--dump-dom", "file://" + fs::absolute(html).string()};
  if (width > 0) args.insert(args.begin(), fmt::format("--window-size={},900", width));
  r.exit_code = RunChromium(args, work_dir, timeout_s, out, err);
  r.dom = ReadFile(out);
  r.log = ReadFile(err);
  std::smatch m;
  const std::regex body(R"(<body\b[^>]*>)");
  if (std::regex_search(r.dom, m, body)) {
    const std::string tag = m.str();
    std::smatch a;
    if (std::regex_search(tag, a, std::regex(R"(data-charts-expected="(\d+)\")"))) {
      r.charts_expected = std::stoi(a[1]);
      r.has_body_marker = true;
    }
    if (std::regex_search(tag, a, std::regex(R"(data-charts-rendered="(\d+)\")"))) {
      r.charts_rendered = std::stoi(a[1]);
    }
    if (std::regex_search(tag, a, std::regex(R"(data-wide-tables="(\d+)\")"))) {
      r.wide_tables = std::stoi(a[1]);
    }
    if (std::regex_search(tag, a, std::regex(R"(data-errors="([^"]*)\")"))) {
      const auto j = nlohmann::json::parse(HtmlUnescape(a[1]), nullptr, false);
      if (j.is_array()) {
        for (const auto& e : j) r.page_errors.push_back(e.is_string() ? e.get<std::string>() : e.dump());
      } else {
        r.page_errors.push_back("unparsable data-errors: " + a[1].str());
      }
    }
  }
  const std::regex canvas(R"(<canvas\b[^>]*data-rendered="1")");
  r.canvases_marked_rendered = static_cast<int>(
      std::distance(std::sregex_iterator(r.dom.begin(), r.dom.end(), canvas), std::sregex_iterator()));
  std::istringstream log(r.log);
  for (std::string line; std::getline(log, line);) {
    if (line.find(":CONSOLE") != std::string::npos) r.console_lines.push_back(line);
  }
  return r;
}

int Screenshot(const fs::path& html, const fs::path& png, const fs::path& work_dir, int width,
               int height, int timeout_s) {
  fs::create_directories(work_dir);
  fs::remove(png);
  return RunChromium({"--hide-scrollbars", fmt::format("--window-size={},{}", width, height),
                      "--screenshot=" + fs::absolute(png).string(),
                      "file://" + fs::absolute(html).string()},
                     work_dir, timeout_s, work_dir / "shot.out", work_dir / "shot.log");
}

InkStats MeasureInk(const fs::path& png) {
  const Image img = ReadPng(png);
  InkStats s;
  s.width = img.width;
  s.height = img.height;
  std::set<int> colors;
  std::size_t ink = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const float* p = img.At(x, y);
      int q = 0;
      bool white = true;
      for (int c = 0; c < 3; ++c) {
        const int v = static_cast<int>(p[c] * 255.0f + 0.5f);
        white = white && v >= 255 - 8;
        q = q * 32 + v / 8;
      }
      if (!white) ++ink;
      colors.insert(q);
    }
  }
  const double pixels = static_cast<double>(img.width) * img.height;
  s.non_white_fraction = pixels > 0 ? static_cast<double>(ink) / pixels : 0;
  s.distinct_colors = static_cast<int>(colors.size());
  return s;
}

}  // namespace brdfit::testing
