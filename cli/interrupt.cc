#include "cli/interrupt.h"

#include <fmt/core.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <mutex>
#include <thread>

#include "io/temp_files.h"

namespace brdfit::cli {
namespace {

std::mutex& HookMutex() {
  static std::mutex* mu = new std::mutex;  // never destroyed: the signal thread outlives main
  return *mu;
}
InterruptHook& Hook() {
  static InterruptHook* hook = new InterruptHook;
  return *hook;
}

sigset_t HandledSignals() {
  sigset_t set;
  sigemptyset(&set);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, s);
  return set;
}

[[noreturn]] void OnSignal(int sig) {
  using namespace std::chrono_literals;
  const int drained = AbandonTemporaries(5s);
  InterruptHook hook;
  {
    std::lock_guard<std::mutex> lock(HookMutex());
    hook = Hook();
  }
  if (hook) {
    hook(sig, drained);
  } else {
    fmt::print(stderr, "\nbrdfit: interrupted\n");
  }
  std::fflush(stdout);
  std::fflush(stderr);
  ::_exit(128 + sig);
}

}  // namespace

void InstallInterruptHandler() {
  const sigset_t set = HandledSignals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);  // inherited by every thread created later
  std::thread([set] {
    int sig = 0;
    while (sigwait(&set, &sig) != 0) {
    }
    OnSignal(sig);
  }).detach();
}

void SetInterruptHook(InterruptHook hook) {
  std::lock_guard<std::mutex> lock(HookMutex());
  Hook() = std::move(hook);
}

}  // namespace brdfit::cli
