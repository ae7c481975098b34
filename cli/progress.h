// Progress of long work (fit batches, bench sweeps, reports over many tables) on stderr.
//
//  * stderr a terminal: a bar redrawn in place, with done/total, elapsed time, the rate of
//    finished items and the ETA (remaining items at the rate so far).
//  * stderr a pipe or file (a job log, `2> log`, Slurm's slurm-%A_%a.out): one line per
//    finished item, time-stamped (UTC, ISO 8601) and flushed, and every
//    BRDFIT_PROGRESS_INTERVAL seconds (default 60; 0: after every item) a summary line with
//    done/total, rate and ETA, and one at the end:
//      2026-12-02T09:30:07Z fitting 3/10 done: gold-paint lambert+ggx (converged)
//      2026-12-02T09:30:07Z fitting 3/10 (30%), 0.42/s, elapsed 7s, ETA 17s
//  * Off when disabled (--quiet, --no-progress, --json -) or $BRDFIT_NO_PROGRESS is set.
//
//   Progress bar(total, "fitting");
//   for (...) { bar.Step(label); ... }     // an item starts; the previous one is finished
//   bar.Done();  // also on destruction
// Callers whose items finish out of order (parallel fits) call CountFinishes() first, then
// Finish(label) as each item finishes; Step then only starts items.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace brdfit::cli {

class Progress {
 public:
  // enabled = false forces silence (e.g. --quiet or --json).
  Progress(std::size_t total, std::string what, bool enabled = true);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void CountFinishes() { explicit_finish_ = true; }  // items end by Finish, not by the next Step
  void Step(const std::string& label);               // starts item number started+1, labelled
  // The item `label` finished (`note`, e.g. its status, in parentheses in the log line).
  void Finish(const std::string& label, const std::string& note = "");
  void Clear();  // erases the bar (call before printing to stdout); the next Step redraws it
  void Done();   // erases the bar for good; in a log, the final summary line

  bool active() const { return mode_ != Mode::kOff; }

 private:
  enum class Mode { kOff, kBar, kLog };
  void Draw();
  void Finished(const std::string& label, const std::string& note);
  void Summary();
  double Elapsed() const;
  std::string RateAndEta() const;

  std::size_t total_, started_ = 0, finished_ = 0;
  std::string what_, label_;
  Mode mode_;
  bool explicit_finish_ = false;  // CountFinishes: Step does not finish items
  bool pending_ = false;          // Step-only callers: label_ started, not yet finished
  double interval_s_ = 60, last_summary_s_ = 0;
  std::chrono::steady_clock::time_point start_;
};

// True when stderr is a terminal and $BRDFIT_NO_PROGRESS is unset.
bool ProgressWanted();

// "2026-12-02T09:30:07Z": now, UTC.
std::string UtcTimestamp();

}  // namespace brdfit::cli
