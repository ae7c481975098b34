// Small threading helpers of the fit layer: the calling thread's CPU time (the FitTimes *_cpu
// fields) and running one body on a few threads (the metric pass, fit/fit_engine.cc and
// fit/metrics.cc).
#pragma once

#include <ctime>
#include <thread>
#include <vector>

namespace brdfit::internal {

// CLOCK_THREAD_CPUTIME_ID in ms: on a busy machine the wall time includes waiting for a core,
// this does not.
inline double ThreadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

// body(t) for t = 0 .. n - 1: t = 0 on the calling thread, the others on threads of their own,
// all joined before it returns.
template <class Body>
void RunOnThreads(int n, const Body& body) {
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back([&body, t] { body(t); });
  body(0);
  for (auto& th : pool) th.join();
}

}  // namespace brdfit::internal
