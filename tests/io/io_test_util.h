// Helpers shared by the io tests: scratch folders, hand-made files, CLI runs.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/table.h"
#include "tests/scratch_dir.h"

namespace brdfit::testing_io {

namespace fs = std::filesystem;

using brdfit::ScratchDir;

inline std::vector<char> ReadBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

inline void WriteBytes(const fs::path& p, const void* data, std::size_t n) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(n));
}

// A double with random mantissa bits and a binary exponent in [emin, emax]: exercises every
// rounding case of the channel scaling, unlike "nice" decimal values.
inline double RandomDouble(std::mt19937_64& rng, int emin, int emax) {
  const std::uint64_t bits = rng();
  const double mantissa = 1.0 + static_cast<double>(bits >> 12) * 0x1p-52;
  const int e = emin + static_cast<int>(rng() % static_cast<std::uint64_t>(emax - emin + 1));
  return std::ldexp(mantissa, e);
}

// A table with random valid values (some cells invalid) on any grid.
inline Table RandomTable(const Grid& g, std::uint64_t seed, double invalid_fraction = 0.2) {
  std::mt19937_64 rng(seed);
  Table t = Table::Empty(g);
  for (std::size_t i = 0; i < g.NumCells(); ++i) {
    t.valid[i] = (rng() % 1000) >= invalid_fraction * 1000;
    for (int c = 0; c < 3; ++c) t.rgb[3 * i + c] = RandomDouble(rng, -12, 8);
  }
  return t;
}

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

inline std::string Quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') {
      q.append("'\\''");
    } else {
      q.push_back(c);
    }
  }
  q.push_back('\'');
  return q;
}

// Runs the brdfit executable with arguments; captures stdout and stderr.
inline CliResult RunCli(const std::vector<std::string>& args, const fs::path& scratch) {
  std::string cmd = Quote(BRDFIT_EXE);
  for (const auto& a : args) {
    cmd.push_back(' ');
    cmd.append(Quote(a));
  }
  const fs::path out = scratch / "cli.stdout", err = scratch / "cli.stderr";
  cmd.append(" >").append(Quote(out.string())).append(" 2>").append(Quote(err.string()));
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  const auto o = ReadBytes(out), e = ReadBytes(err);
  r.out.assign(o.begin(), o.end());
  r.err.assign(e.begin(), e.end());
  return r;
}

inline int CountLines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n + (!s.empty() && s.back() != '\n');
}

}  // namespace brdfit::testing_io
