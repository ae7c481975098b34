#include "cli/progress.h"
#include "cli/terminal_text.h"

#include <fmt/core.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>

namespace brdfit::cli {
namespace {

bool ProgressOff() {
  const char* off = std::getenv("BRDFIT_NO_PROGRESS");
  return off && *off;
}

// $BRDFIT_PROGRESS_INTERVAL in seconds (>= 0), else 60.
double SummaryInterval() {
  const char* s = std::getenv("BRDFIT_PROGRESS_INTERVAL");
  if (!s || !*s) return 60;
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  return end && *end == '\0' && std::isfinite(v) && v >= 0 ? v : 60;
}

// "7s", "3m05s", "2h04m".
std::string Duration(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  const long t = std::lround(s);
  if (t < 60) return fmt::format("{}s", t);
  if (t < 3600) return fmt::format("{}m{:02d}s", t / 60, t % 60);
  return fmt::format("{}h{:02d}m", t / 3600, (t / 60) % 60);
}

}  // namespace

bool ProgressWanted() {
  return isatty(STDERR_FILENO) == 1 && !ProgressOff();
}

std::string UtcTimestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

Progress::Progress(std::size_t total, std::string what, bool enabled)
    : total_(total),
      what_(std::move(what)),
      mode_(!enabled || total == 0 || ProgressOff() ? Mode::kOff
            : isatty(STDERR_FILENO) == 1            ? Mode::kBar
                                                    : Mode::kLog),
      interval_s_(SummaryInterval()),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
  Done();
}

double Progress::Elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

// "0.42/s, elapsed 7s, ETA 17s" (items per second, or seconds per item when slower than 1/min).
std::string Progress::RateAndEta() const {
  const double elapsed = Elapsed();
  if (finished_ == 0 || elapsed <= 0) return fmt::format("elapsed {}, ETA ?", Duration(elapsed));
  const double rate = static_cast<double>(finished_) / elapsed;
  const std::string r =
      rate >= 1.0 / 60 ? fmt::format("{:.3g}/s", rate) : fmt::format("{}/item", Duration(1 / rate));
  const double eta = static_cast<double>(total_ - std::min(finished_, total_)) / rate;
  return fmt::format("{}, elapsed {}, ETA {}", r, Duration(elapsed), Duration(eta));
}

void Progress::Step(const std::string& label) {
  if (mode_ == Mode::kOff) return;
  if (mode_ == Mode::kLog && pending_ && !explicit_finish_) Finished(label_, "");
  if (started_ < total_) ++started_;
  if (mode_ == Mode::kBar && !explicit_finish_ && started_ > 1) finished_ = started_ - 1;
  label_ = TerminalSafe(label);  // names from files: never raw control bytes
  pending_ = true;
  if (mode_ == Mode::kBar) Draw();
}

void Progress::Finish(const std::string& label, const std::string& note) {
  if (mode_ == Mode::kOff) return;
  if (mode_ == Mode::kLog) {
    Finished(label, note);
    return;
  }
  if (finished_ < total_) ++finished_;
  Draw();
}

void Progress::Finished(const std::string& label, const std::string& note) {
  if (finished_ < total_) ++finished_;
  pending_ = false;
  fmt::print(stderr, "{} {} {}/{} done: {}{}\n", UtcTimestamp(), what_, finished_, total_,
             TerminalSafe(label), note.empty() ? "" : " (" + TerminalSafe(note) + ")");
  const double now = Elapsed();
  if (now - last_summary_s_ >= interval_s_ && finished_ < total_) {
    Summary();
    last_summary_s_ = now;
  }
  std::fflush(stderr);
}

void Progress::Summary() {
  const double pct = total_ ? 100.0 * static_cast<double>(finished_) / total_ : 100;
  fmt::print(stderr, "{} {} {}/{} ({:.0f}%), {}\n", UtcTimestamp(), what_, finished_, total_, pct,
             RateAndEta());
}

void Progress::Draw() {
  constexpr int kWidth = 24;
  const int filled = static_cast<int>(kWidth * std::min(finished_, total_) / total_);
  std::string bar(filled, '#');
  bar.resize(kWidth, '.');
  std::string label = label_;
  if (label.size() > 40) label = "..." + label.substr(label.size() - 37);
  // \r + erase to end of line: the bar redraws in place.
  fmt::print(stderr, "\r\x1b[2K{} [{}] {}/{} {} {}", what_, bar, started_, total_, RateAndEta(),
             label);
  std::fflush(stderr);
}

void Progress::Clear() {
  if (mode_ != Mode::kBar) return;
  fmt::print(stderr, "\r\x1b[2K");
  std::fflush(stderr);
}

void Progress::Done() {
  if (mode_ == Mode::kLog) {
    if (pending_ && !explicit_finish_) Finished(label_, "");
    Summary();
    std::fflush(stderr);
  }
  Clear();
  mode_ = Mode::kOff;
}

}  // namespace brdfit::cli
