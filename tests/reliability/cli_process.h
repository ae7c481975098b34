// Running the brdfit executable as a child process (signals, concurrent runs): start it with
// its output to a log file, wait for it, read files back.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern char** environ;

namespace brdfit::testing_cli {

inline std::string ReadAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Starts `brdfit args...` with stdout and stderr to `log`; returns the pid.
inline pid_t Spawn(const std::vector<std::string>& args, const std::filesystem::path& log) {
  std::vector<std::string> argv_s = {BRDFIT_EXE};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, BRDFIT_EXE, &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  EXPECT_EQ(rc, 0) << "cannot start " << BRDFIT_EXE;
  return pid;
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
