// A test hook of the batch fit runner (pipeline/batch_fit.h): hold a running batch at a known
// point so that a test can signal or kill it there, whatever the machine's speed.
//
// Read from the environment, by the batch runner only; unset (every user run) it does nothing:
//   BRDFIT_TEST_HOLD_FILE=PATH     where to hold: the runner creates PATH (holding its pid) and
//                                  blocks while PATH exists (at most 10 minutes, then goes on);
//   BRDFIT_TEST_HOLD_AFTER_FITS=K  when: K = 0 holds before the first fit starts (the report's
//                                  lock held, nothing fitted); K > 0 writes a checkpoint as the
//                                  K-th fit of the run finishes and holds right after it, so the
//                                  report on disk holds the kept entries plus exactly K fits.
// A test waits for PATH to appear, then sends its signal (or removes PATH to let the run go on).
// docs/reliability.md, "Tests that interrupt a batch".
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>

namespace brdfit::pipeline {

class BatchHold {
 public:
  // From the environment; inactive unless both variables are set and valid.
  static BatchHold FromEnvironment();

  bool Active() const { return after_fits_.has_value(); }
  // True when the runner is to write a checkpoint now, `fits_done` fits into the run.
  bool CheckpointAfter(std::size_t fits_done) const {
    return after_fits_ && *after_fits_ > 0 && fits_done == *after_fits_;
  }
  // Holds if `fits_done` is the hold point (see above); returns at once otherwise.
  void HoldAt(std::size_t fits_done) const;

 private:
  std::filesystem::path file_;
  std::optional<std::size_t> after_fits_;
};

}  // namespace brdfit::pipeline
