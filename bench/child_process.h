// Running the brdfit executable as a child process for the whole-command benchmarks
// (bench_*_cli): wall time, the child's peak RSS (wait4's ru_maxrss, as /usr/bin/time -v
// reports it) and a timeout.
#pragma once

#include <fcntl.h>
#include <fmt/core.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace brdfit::bench {

struct ChildRun {
  double seconds = 0;      // wall time from spawn to exit
  double cpu_seconds = 0;  // user + system CPU time of the child (less sensitive to load)
  double peak_rss_mb = 0;  // ru_maxrss of the child, MiB
  int exit_code = -1;      // exit status, or 128 + signal
  bool timed_out = false;  // killed after the timeout
};

// Runs `exe args...` with stdout and stderr into `log`. Exits the program if exe cannot start.
// The child runs under /usr/bin/time (package time) when present, which reports its peak RSS
// and CPU time: a child spawned straight from this process would inherit the benchmark's own
// high-water mark in ru_maxrss (Linux carries it over exec), and this process holds the tables
// it wrote.
inline ChildRun RunChild(const std::string& exe, const std::vector<std::string>& args,
                         double timeout_s, const std::filesystem::path& log) {
  using Clock = std::chrono::steady_clock;
  const std::filesystem::path time_out = log.string() + ".time";
  const bool timed = ::access("/usr/bin/time", X_OK) == 0;
  std::vector<std::string> argv_s;
  if (timed) argv_s = {"/usr/bin/time", "-f", "%M %U %S", "-o", time_out.string()};
  argv_s.push_back(exe);
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = -1;
  const auto t0 = Clock::now();
  const int rc = posix_spawn(&pid, argv_s[0].c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) {
    fmt::print(stderr, "cannot start {}: {}\n", exe, std::strerror(rc));
    std::exit(2);
  }
  ChildRun run;
  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, WNOHANG, &usage) == 0) {
    if (std::chrono::duration<double>(Clock::now() - t0).count() > timeout_s) {
      kill(pid, SIGKILL);
      wait4(pid, &status, 0, &usage);
      run.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  run.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (timed) {
    // /usr/bin/time exits with the command's status; its -o file holds "KiB user system".
    std::FILE* f = std::fopen(time_out.c_str(), "r");
    double kib = 0, user = 0, sys = 0;
    if (f) {
      // A non-zero exit adds a "Command exited with non-zero status" line first.
      char line[256];
      while (std::fgets(line, sizeof line, f)) {
        if (std::sscanf(line, "%lf %lf %lf", &kib, &user, &sys) == 3) break;
      }
      std::fclose(f);
    }
    run.peak_rss_mb = kib / 1024.0;
    run.cpu_seconds = user + sys;
  } else {
    run.peak_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // an upper bound
    auto sec = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * t.tv_usec; };
    run.cpu_seconds = sec(usage.ru_utime) + sec(usage.ru_stime);
  }
  return run;
}

inline double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The 1-minute load average, to quote with every measurement.
inline double LoadAverage() {
  double load[1] = {0};
  return getloadavg(load, 1) == 1 ? load[0] : -1;
}

}  // namespace brdfit::bench
