// Running the brdfit executable as a child process (signals, concurrent runs): start it with
// its output to a log file, wait for it, read files back.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace brdfit::testing_cli {

inline std::string ReadAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Starts `brdfit args...` with stdout and stderr to `log`, and `extra_env` ("NAME=value")
// added to this process's environment; returns the pid.
inline pid_t Spawn(const std::vector<std::string>& args, const std::filesystem::path& log,
                   const std::vector<std::string>& extra_env = {}) {
  std::vector<std::string> argv_s = {BRDFIT_EXE};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  std::vector<std::string> env_s(extra_env);
  for (char** e = environ; *e; ++e) env_s.push_back(*e);  // the first of a name wins
  std::vector<char*> envp;
  for (auto& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, BRDFIT_EXE, &fa, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&fa);
  EXPECT_EQ(rc, 0) << "cannot start " << BRDFIT_EXE;
  return pid;
}

// Starts a batch `brdfit fit ...` that holds itself at a known point through the batch runner's
// test hook (pipeline/batch_hold.h): after the checkpoint of its `after_fits`-th fit (0: before
// its first fit, its report's lock held). There it creates `hold` and waits while `hold`
// exists; the test signals it, kills it, or removes `hold` to let it go on.
inline pid_t SpawnHeld(const std::vector<std::string>& args, const std::filesystem::path& log,
                       const std::filesystem::path& hold, std::size_t after_fits) {
  std::filesystem::remove(hold);
  return Spawn(args, log,
               {"BRDFIT_TEST_HOLD_FILE=" + hold.string(),
                "BRDFIT_TEST_HOLD_AFTER_FITS=" + std::to_string(after_fits)});
}

// Waits until `path` exists; false if the process ended first (it is reaped then) or ten
// minutes passed. The only wait of these tests: it ends on an event, never on a duration.
inline bool WaitForFile(const std::filesystem::path& path, pid_t pid) {
  using namespace std::chrono_literals;
  for (auto t0 = std::chrono::steady_clock::now();
       std::chrono::steady_clock::now() - t0 < 10min;) {
    if (std::filesystem::exists(path)) return true;
    if (waitpid(pid, nullptr, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(5ms);
  }
  return false;
}

// The exit code, or 128 + the signal that ended the process.
inline int Wait(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

struct CliRun {
  int code;
  std::string log;  // stdout and stderr together
};

// Runs `brdfit args...` to completion with its output in `log`.
inline CliRun Run(const std::vector<std::string>& args, const std::filesystem::path& log) {
  const int code = Wait(Spawn(args, log));
  return {code, ReadAll(log)};
}

}  // namespace brdfit::testing_cli
