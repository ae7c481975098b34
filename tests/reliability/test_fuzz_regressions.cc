// Replays every committed fuzz input (fuzz/corpus/<harness>/* seeds and
// fuzz/regressions/<harness>/* crashing or hostile inputs) through the same harness code the
// fuzzers run (fuzz/fuzz_<harness>.cc), built normally. A harness throws on anything but a
// clean InputError or a successful read that satisfies the format's invariants, so a
// regression of a fixed finding fails here (and under ASan + UBSan in `make test-asan`).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/harness_util.h"

namespace brdfit::fuzz {
namespace {

namespace fs = std::filesystem;

using Harness = int (*)(const std::uint8_t*, std::size_t);

struct Harnesses {
  const char* name;
  Harness fn;
};
constexpr Harnesses kHarnesses[] = {
    {"merl", FuzzMerl},
    {"hdf5_table", FuzzHdf5Table},
    {"nbrdf", FuzzNbrdf},
    {"exr", FuzzExr},
    {"factor_sidecar", FuzzFactorSidecar},
    {"scene", FuzzScene},
    {"fit_report", FuzzFitReport},
    {"mesh", FuzzMesh},
    {"factor_files", FuzzFactorFiles},
    {"bench_csv", FuzzBenchCsv},
    {"render_cache", FuzzRenderCache},
    {"rgl_bsdf", FuzzRglBsdf},
};

struct Input {
  std::string harness;
  Harness fn;
  fs::path file;
};

std::vector<Input> CommittedInputs() {
  std::vector<Input> out;
  const fs::path root = fs::path(BRDFIT_SOURCE_DIR) / "fuzz";
  for (const auto& h : kHarnesses) {
    for (const char* kind : {"corpus", "regressions"}) {
      const fs::path dir = root / kind / h.name;
      if (!fs::is_directory(dir)) continue;
      std::vector<fs::path> files;
      for (const auto& e : fs::directory_iterator(dir)) {
        if (e.is_regular_file()) files.push_back(e.path());
      }
      std::sort(files.begin(), files.end());
      for (const auto& f : files) out.push_back({h.name, h.fn, f});
    }
  }
  return out;
}

std::string TestName(const ::testing::TestParamInfo<Input>& info) {
  std::string s = info.param.harness + "_" + info.param.file.parent_path().filename().string() +
                  "_" + info.param.file.filename().string();
  for (char& c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return s + "_" + std::to_string(info.index);
}

class FuzzInputs : public ::testing::TestWithParam<Input> {};

TEST_P(FuzzInputs, ReaderRejectsCleanlyOrReadsConsistently) {
  std::ifstream in(GetParam().file, std::ios::binary);
  ASSERT_TRUE(in) << GetParam().file;
  const std::vector<char> bytes(std::istreambuf_iterator<char>(in), {});
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  EXPECT_NO_THROW(GetParam().fn(data, bytes.size())) << GetParam().file;
}

INSTANTIATE_TEST_SUITE_P(Committed, FuzzInputs, ::testing::ValuesIn(CommittedInputs()), TestName);

// Every harness has seeds: an empty folder would make the suite above pass vacuously.
TEST(FuzzInputs, EveryHarnessHasSeeds) {
  for (const auto& h : kHarnesses) {
    const fs::path dir = fs::path(BRDFIT_SOURCE_DIR) / "fuzz" / "corpus" / h.name;
    ASSERT_TRUE(fs::is_directory(dir)) << dir;
    EXPECT_FALSE(fs::is_empty(dir)) << dir;
  }
}

}  // namespace
}  // namespace brdfit::fuzz
