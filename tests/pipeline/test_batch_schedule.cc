// The order in which a batch's workers take its tasks (pipeline/batch_schedule.h): no worker
// waits for another's table while a task it could run, or an input it could load, is left.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "pipeline/batch_schedule.h"

namespace brdfit::pipeline {
namespace {

TEST(BatchSchedule, AWorkerLoadsTheNextInputRatherThanWaitForAnother) {
  // Three inputs of two tasks each: tasks 0-1 (input 0), 2-3 (input 1), 4-5 (input 2).
  BatchSchedule s({0, 0, 1, 1, 2, 2});
  EXPECT_EQ(s.Next(), 0u);  // worker A loads input 0
  EXPECT_EQ(s.Next(), 2u);  // worker B: input 0 is being loaded, so it loads input 1
  s.MarkLoaded(0);
  EXPECT_EQ(s.Next(), 1u);  // A: the loaded input's task before a new input
  EXPECT_EQ(s.Next(), 4u);  // input 1 still loading: input 2 is loaded next
  // Every input claimed, none of the open tasks' inputs loaded: the first one, which waits.
  EXPECT_EQ(s.Next(), 3u);
  s.MarkLoaded(2);
  EXPECT_EQ(s.Next(), 5u);
  EXPECT_EQ(s.Next(), std::nullopt);
}

TEST(BatchSchedule, OpenInputsAreFinishedBeforeANewOneIsLoaded) {
  BatchSchedule s({0, 0, 0, 1, 1});
  EXPECT_EQ(s.Next(), 0u);
  s.MarkLoaded(0);
  EXPECT_EQ(s.Next(), 1u);
  EXPECT_EQ(s.Next(), 2u);
  EXPECT_EQ(s.Next(), 3u);
  EXPECT_EQ(s.Next(), 4u);  // input 1 claimed and not loaded: nothing else is left
  EXPECT_EQ(s.Next(), std::nullopt);
}

TEST(BatchSchedule, InputsWithoutTasksAndStop) {
  // Inputs 1 and 2 have no tasks (done before, or in another shard).
  BatchSchedule s({0, 3, 3});
  EXPECT_EQ(s.Next(), 0u);
  EXPECT_EQ(s.Next(), 1u);
  s.Stop();
  EXPECT_EQ(s.Next(), std::nullopt);
  BatchSchedule empty({});
  EXPECT_EQ(empty.Next(), std::nullopt);
}

TEST(BatchSchedule, WorkersTakeEveryTaskExactlyOnce) {
  std::vector<std::size_t> inputs;
  for (std::size_t in = 0; in < 200; ++in) {
    for (std::size_t k = 0; k < 1 + in % 4; ++k) inputs.push_back(in);
  }
  BatchSchedule s(inputs);
  std::vector<std::atomic<int>> count(inputs.size());
  std::vector<std::thread> pool;
  for (int w = 0; w < 4; ++w) {
    pool.emplace_back([&] {
      while (const auto i = s.Next()) {
        ++count[*i];
        s.MarkLoaded(inputs[*i]);
      }
    });
  }
  for (auto& t : pool) t.join();
  EXPECT_TRUE(std::all_of(count.begin(), count.end(), [](const auto& c) { return c == 1; }));
}

}  // namespace
}  // namespace brdfit::pipeline
