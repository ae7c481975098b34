#include "pipeline/batch_schedule.h"

#include <utility>

namespace brdfit::pipeline {

BatchSchedule::BatchSchedule(std::vector<std::size_t> task_inputs)
    : input_of_(std::move(task_inputs)), taken_(input_of_.size(), 0) {
  const std::size_t inputs = input_of_.empty() ? 0 : input_of_.back() + 1;
  claimed_.assign(inputs, 0);
  loaded_.assign(inputs, 0);
}

std::optional<std::size_t> BatchSchedule::Next() {
  std::lock_guard<std::mutex> lock(mu_);
  if (stopped_) return std::nullopt;
  while (first_open_ < taken_.size() && taken_[first_open_]) ++first_open_;
  std::optional<std::size_t> waiting;  // the first open task of an input being loaded
  // Inputs are claimed in order: the scan ends at the first unclaimed one, so it covers only
  // the inputs in progress.
  for (std::size_t i = first_open_; i < taken_.size(); ++i) {
    if (taken_[i]) continue;
    const std::size_t in = input_of_[i];
    if (!loaded_[in] && claimed_[in]) {
      if (!waiting) waiting = i;
      continue;
    }
    claimed_[in] = 1;
    taken_[i] = 1;
    return i;
  }
  if (waiting) taken_[*waiting] = 1;
  return waiting;
}

void BatchSchedule::MarkLoaded(std::size_t input) {
  std::lock_guard<std::mutex> lock(mu_);
  loaded_[input] = 1;
}

void BatchSchedule::Stop() {
  std::lock_guard<std::mutex> lock(mu_);
  stopped_ = true;
}

}  // namespace brdfit::pipeline
