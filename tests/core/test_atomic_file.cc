#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "io/atomic_file.h"
#include "core/error.h"

namespace brdfit {
namespace {
namespace fs = std::filesystem;

std::string ReadAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("brdfit_atomic_" + std::to_string(::getpid()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(AtomicFileTest, WritesAndReplaces) {
  const fs::path p = dir_ / "out.txt";
  WriteTextAtomically(p, "first");
  WriteTextAtomically(p, "second");
  EXPECT_EQ(ReadAll(p), "second");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}), 1);
}

TEST_F(AtomicFileTest, FailedWriteLeavesOldContentAndNoTemporary) {
  const fs::path p = dir_ / "out.txt";
  WriteTextAtomically(p, "keep me");
  EXPECT_THROW(WriteFileAtomically(p,
                                   [](const fs::path& tmp) {
                                     std::ofstream(tmp) << "half";
                                     throw std::runtime_error("crash mid-write");
                                   }),
               std::runtime_error);
  EXPECT_EQ(ReadAll(p), "keep me");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}), 1);
}

TEST_F(AtomicFileTest, TwoFilesAreReplacedTogetherOrNotAtAll) {
  const fs::path a = dir_ / "m.gltf", b = dir_ / "m.bin";
  WriteTwoFilesAtomically(a, "json 1", b, "bin 1", 5);
  EXPECT_EQ(ReadAll(a), "json 1");
  EXPECT_EQ(ReadAll(b), "bin 1");
  // The first cannot be renamed into place (a folder took its name): the second stays old.
  fs::remove(a);
  fs::create_directory(a);
  EXPECT_THROW(WriteTwoFilesAtomically(a, "json 2", b, "bin 2", 5), OutputError);
  EXPECT_EQ(ReadAll(b), "bin 1");
  // The second cannot be written: the first stays old.
  fs::remove(a);
  WriteTextAtomically(a, "json 1");
  fs::remove(b);
  fs::create_directory(b);
  EXPECT_THROW(WriteTwoFilesAtomically(a, "json 2", b, "bin 2", 5), OutputError);
  EXPECT_EQ(ReadAll(a), "json 1");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}), 2);
}

TEST_F(AtomicFileTest, DirectoryDestinationIsAnError) {
  EXPECT_THROW(WriteTextAtomically(dir_, "x"), OutputError);
}

}  // namespace
}  // namespace brdfit
