#include "cli/progress.h"

#include <fmt/core.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace brdfit::cli {

bool ProgressWanted() {
  const char* off = std::getenv("BRDFIT_NO_PROGRESS");
  return isatty(STDERR_FILENO) == 1 && !(off && *off);
}

Progress::Progress(std::size_t total, std::string what, bool enabled)
    : total_(total),
      what_(std::move(what)),
      active_(enabled && total > 0 && ProgressWanted()),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
  Done();
}

void Progress::Step(const std::string& label) {
  if (!active_) return;
  if (done_ < total_) ++done_;
  label_ = label;
  Draw();
}

void Progress::Draw() {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  constexpr int kWidth = 24;
  const int filled = static_cast<int>(kWidth * (done_ - 1) / total_);
  std::string bar(filled, '#');
  bar.resize(kWidth, '.');
  std::string label = label_;
  if (label.size() > 40) label = "..." + label.substr(label.size() - 37);
  // \r + erase to end of line: the bar redraws in place.
  fmt::print(stderr, "\r\x1b[2K{} [{}] {}/{} {:.0f}s {}", what_, bar, done_, total_, elapsed,
             label);
  std::fflush(stderr);
}

void Progress::Clear() {
  if (!active_) return;
  fmt::print(stderr, "\r\x1b[2K");
  std::fflush(stderr);
}

void Progress::Done() {
  Clear();
  active_ = false;
}

}  // namespace brdfit::cli
