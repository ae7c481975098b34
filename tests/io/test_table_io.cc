// LoadTable/SaveTable (io/table_io.h): the format comes from the content, not the name.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/merl.h"
#include "io/table_io.h"
#include "io_test_util.h"

namespace brdfit {
namespace {

using testing_io::ScratchDir;

TEST(TableIo, FormatIsDetectedByContentNotByName) {
  ScratchDir dir;
  Table small = testing_io::RandomTable(Grid{3, 3, 6, ThetaHMapping::kLinear}, 1);
  SaveTable(small, dir / "really-hdf5.binary", TableFormat::kHdf5);
  LoadReport report;
  EXPECT_EQ(LoadTable(dir / "really-hdf5.binary", &report), small);
  EXPECT_EQ(report.format, TableFormat::kHdf5);

  Table merl = Table::Empty(Grid::Merl());
  for (std::size_t i = 0; i < merl.valid.size(); i += 2) merl.valid[i] = 1;
  SaveTable(merl, dir / "really-merl.h5", TableFormat::kMerl);
  EXPECT_EQ(DetectTableFormat(dir / "really-merl.h5"), TableFormat::kMerl);
  const Table back = LoadTable(dir / "really-merl.h5", &report);
  EXPECT_EQ(report.format, TableFormat::kMerl);
  EXPECT_EQ(report.negative_cells, merl.valid.size() / 2);
  EXPECT_EQ(back.valid, merl.valid);
}

TEST(TableIo, SaveChoosesTheFormatFromTheExtension) {
  ScratchDir dir;
  const Table t = testing_io::RandomTable(Grid{2, 2, 4, ThetaHMapping::kSqrt}, 2);
  SaveTable(t, dir / "t.H5");
  EXPECT_EQ(DetectTableFormat(dir / "t.H5"), TableFormat::kHdf5);
  EXPECT_EQ(TableFormatFromExtension(dir / "x.binary"), TableFormat::kMerl);
  EXPECT_EQ(TableFormatFromExtension(dir / "x.hdf5"), TableFormat::kHdf5);
  EXPECT_EQ(TableFormatFromExtension(dir / "x.txt"), std::nullopt);
  EXPECT_THROW(SaveTable(t, dir / "t.txt"), InputError);
  EXPECT_THROW(FromString<TableFormat>("exr"), InputError);
}

TEST(TableIo, MissingAndDirectoryInputsAreNamed) {
  ScratchDir dir;
  EXPECT_THAT([&] { LoadTable(dir / "none"); },
              ::testing::ThrowsMessage<InputError>((dir / "none").string() + ": no such file"));
  EXPECT_THAT([&] { LoadTable(dir.path()); },
              ::testing::ThrowsMessage<InputError>(dir.path().string() + ": is a directory"));
}

}  // namespace
}  // namespace brdfit
