// The fixture of the material-key and shard tests: three small lambert+ggx tables
// DIR/lab/a/x.h5, DIR/lab/b/x.h5 (the same stem in another folder) and DIR/lab/a/y.h5, each
// with its own roughness, and the CLI run in DIR.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/synth.h"
#include "io/hdf5_table.h"
#include "models/registry.h"

namespace brdfit::testing {

inline std::string ReadAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

class LabTables : public ::testing::Test {
 protected:
  // lambert+ggx parameters `colours` (kd RGB, ks RGB) with alpha = alpha0 + i dalpha for the
  // i-th table, 2 % noise with seed seed0 + i, on a 16 x 16 x 32 grid; the folder's name has tag.
  void MakeTables(const std::string& tag, const std::vector<double>& colours, double alpha0,
                  double dalpha, std::uint64_t seed0) {
    dir_ = std::filesystem::temp_directory_path() /
           ("brdfit-" + tag + "-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    Grid g;
    g.n_theta_h = 16;
    g.n_theta_d = 16;
    g.n_phi_d = 32;
    const ModelInfo* m = FindModel("lambert+ggx");
    const std::vector<std::string> names = {"a/x.h5", "b/x.h5", "a/y.h5"};
    for (std::size_t i = 0; i < names.size(); ++i) {
      std::vector<double> p = colours;
      p.push_back(alpha0 + dalpha * static_cast<double>(i));
      SynthOptions so;
      so.noise = 0.02;
      so.seed = seed0 + i;
      const Table t = SynthesizeTable(
          g, [&](const Geometry& geo, double rgb[3]) { m->eval(p.data(), geo, rgb); }, so);
      std::filesystem::create_directories((dir_ / "lab" / names[i]).parent_path());
      WriteHdf5Table(t, dir_ / "lab" / names[i]);
    }
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  // `brdfit ARGS` run in the test folder (SOURCE_DATE_EPOCH set: fixed dates); the exit code,
  // and stdout and stderr in *log.
  int Run(const std::string& args, std::string* log) {
    const std::string cmd = "cd '" + dir_.string() + "' && SOURCE_DATE_EPOCH=1700000000 '" +
                            std::string(BRDFIT_EXE) + "' " + args + " > cli.log 2>&1";
    const int status = std::system(cmd.c_str());
    *log = ReadAll(dir_ / "cli.log");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::filesystem::path dir_;
};

}  // namespace brdfit::testing
