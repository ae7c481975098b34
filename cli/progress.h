// A progress bar on stderr for long work (bench sweeps, reports over many tables). Drawn only
// when stderr is a terminal and not disabled; otherwise silent, so logs and pipes stay clean.
//
//   Progress bar(total, "fitting");
//   for (...) { bar.Step(label); ... }
//   bar.Done();  // also on destruction
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

  void Step(const std::string& label);  // starts item number done+1, labelled
  void Clear();  // erases the bar (call before printing to stdout); the next Step redraws it
  void Done();   // erases the bar for good

  bool active() const { return active_; }

 private:
  void Draw();

  std::size_t total_, done_ = 0;
  std::string what_, label_;
  bool active_;
  std::chrono::steady_clock::time_point start_;
};

// True when stderr is a terminal and $BRDFIT_NO_PROGRESS is unset.
bool ProgressWanted();

}  // namespace brdfit::cli
