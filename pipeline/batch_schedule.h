#pragma once
// The order in which a batch's workers take its fit tasks (pipeline/batch_fit.cc).
//
// The tasks of one input (its models) are contiguous and the inputs come in order; each input
// is loaded (read, tabulated, prepared) by the first worker that takes one of its tasks, and
// that worker's peers would wait for it. A worker is handed, in this order of preference:
//   1. a task of an input already loaded (finishing open inputs first keeps few tables alive);
//   2. the first task of the next input nobody loads yet (this worker loads it);
//   3. only when neither is left, a task of an input another worker is loading (it waits).
// Taken in plain order, a batch of NBRDF proxies with four models and two workers had one
// worker waiting through every table's tabulation (docs/fitting.md, "Whole command").

#include <cstddef>
#include <mutex>
#include <optional>
#include <vector>

namespace brdfit::pipeline {

class BatchSchedule {
 public:
  // task_inputs[i]: the input of task i, non-decreasing.
  explicit BatchSchedule(std::vector<std::size_t> task_inputs);

  // The next task for a worker, or nothing when every task is taken or the run stopped.
  std::optional<std::size_t> Next();
  // The input's table is loaded, or failed to load: its tasks run without waiting.
  void MarkLoaded(std::size_t input);
  // Hand out nothing more (a checkpoint could not be written).
  void Stop();

 private:
  std::mutex mu_;
  std::vector<std::size_t> input_of_;
  std::vector<char> taken_;
  std::vector<char> claimed_, loaded_;  // per input: some worker took a task / it is loaded
  std::size_t first_open_ = 0;          // every task before it is taken
  bool stopped_ = false;
};

}  // namespace brdfit::pipeline
