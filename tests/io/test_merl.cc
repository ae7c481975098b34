// MERL binary reader/writer (io/merl.h) against MERL's BRDFRead.cpp: header, size, layout, channel
// scales, masking; round trips; one test per rejected input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/error.h"
#include "io/merl.h"
#include "io_test_util.h"

namespace brdfit {
namespace {

using ::testing::HasSubstr;
using testing_io::ReadBytes;
using testing_io::ScratchDir;

constexpr std::size_t kCells = 90 * 90 * 180;

// A MERL file written byte by byte from the format description (not by WriteMerl).
struct RawMerl {
  std::int32_t dims[3] = {90, 90, 180};
  std::vector<double> body = std::vector<double>(3 * kCells, 0.0);  // channel-planar

  void Write(const std::filesystem::path& p, std::size_t truncate_body_to = SIZE_MAX) const {
    std::vector<char> bytes(12 + body.size() * 8);
    std::memcpy(bytes.data(), dims, 12);
    std::memcpy(bytes.data() + 12, body.data(), body.size() * 8);
    if (truncate_body_to != SIZE_MAX) bytes.resize(12 + truncate_body_to);
    testing_io::WriteBytes(p, bytes.data(), bytes.size());
  }
};

// idx = i_phi_d + 180 i_theta_d + 16200 i_theta_h (BRDFRead.cpp).
std::size_t MerlIndex(int ih, int id, int ip) {
  return ip + 180 * id + 16200 * ih;
}

RawMerl RandomForeignFile(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  RawMerl m;
  for (std::size_t i = 0; i < kCells; ++i) {
    const bool invalid = rng() % 4 == 0;
    for (int c = 0; c < 3; ++c) {
      double r = testing_io::RandomDouble(rng, -4, 14);
      if (invalid && (c == 0 || rng() % 2)) r = (rng() % 2) ? -1.0 : -r;
      m.body[c * kCells + i] = r;
    }
  }
  return m;
}

std::string ErrorOf(const std::filesystem::path& p) {
  try {
    ReadMerl(p);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MerlRead, LayoutChannelScalesAndMaskFollowTheFormat) {
  ScratchDir dir;
  RawMerl m;
  const std::size_t a = MerlIndex(3, 4, 5), b = MerlIndex(89, 0, 179), neg = MerlIndex(1, 2, 3);
  for (int c = 0; c < 3; ++c) {
    m.body[c * kCells + a] = 1500.0 * (c + 1);
    m.body[c * kCells + b] = 0.1 + c;
  }
  m.body[1 * kCells + neg] = -1.0;  // one negative channel masks the whole cell
  m.Write(dir / "m.binary");
  MerlReadReport report;
  const Table t = ReadMerl(dir / "m.binary", &report);
  EXPECT_EQ(t.grid, Grid::Merl());
  const double scale[3] = {1.0 / 1500, 1.15 / 1500, 1.66 / 1500};  // BRDFRead.cpp
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(t.Value(a)[c], 1500.0 * (c + 1) * scale[c]);
    EXPECT_EQ(t.Value(b)[c], (0.1 + c) * scale[c]);
  }
  EXPECT_EQ(t.Value(a)[0], 1.0);
  EXPECT_FALSE(t.valid[neg]);
  EXPECT_EQ(report.negative_cells, 1u);
  EXPECT_EQ(t.CountValid(), kCells - 1);
  EXPECT_EQ(t.provenance.generator, "merl");
  EXPECT_EQ(t.provenance.source, (dir / "m.binary").string());
}

TEST(MerlRead, NegativeZeroIsAValidZero) {
  ScratchDir dir;
  RawMerl m;
  m.body[7] = -0.0;
  m.Write(dir / "m.binary");
  const Table t = ReadMerl(dir / "m.binary");
  EXPECT_TRUE(t.valid[7]);
  EXPECT_EQ(t.Value(7)[0], 0.0);
}

// File -> Table -> file -> Table: the tables are identical (every double, the mask) and the
// file brdfit wrote survives a further round trip byte for byte.
TEST(MerlRoundTrip, TableFromFileIsExactAndWrittenFilesAreByteStable) {
  ScratchDir dir;
  RandomForeignFile(1).Write(dir / "foreign.binary");
  const Table t1 = ReadMerl(dir / "foreign.binary");
  WriteMerl(t1, dir / "a.binary");
  const Table t2 = ReadMerl(dir / "a.binary");
  EXPECT_EQ(t1.valid, t2.valid);
  ASSERT_EQ(t1.rgb.size(), t2.rgb.size());
  EXPECT_EQ(std::memcmp(t1.rgb.data(), t2.rgb.data(), t1.rgb.size() * 8), 0);
  WriteMerl(t2, dir / "b.binary");
  EXPECT_EQ(ReadBytes(dir / "a.binary"), ReadBytes(dir / "b.binary"));
}

// A foreign raw that shares its scaled value with a neighbouring double cannot be restored
// from a double table (docs/formats.md); it comes back at most one ulp away and its scaled
// value is unchanged. Raws that are canonical come back identical.
TEST(MerlRoundTrip, ForeignRawsComeBackWithinOneUlp) {
  ScratchDir dir;
  const RawMerl m = RandomForeignFile(2);
  m.Write(dir / "foreign.binary");
  WriteMerl(ReadMerl(dir / "foreign.binary"), dir / "copy.binary");
  const auto bytes = ReadBytes(dir / "copy.binary");
  ASSERT_EQ(bytes.size(), kMerlFileBytes);
  std::vector<double> copy(3 * kCells);
  std::memcpy(copy.data(), bytes.data() + 12, copy.size() * 8);
  std::size_t changed = 0;
  for (std::size_t k = 0; k < copy.size(); ++k) {
    const double s = kMerlChannelScale[k / kCells];
    if (copy[k] == m.body[k]) continue;
    ++changed;
    ASSERT_TRUE(copy[k] == std::nextafter(m.body[k], HUGE_VAL) ||
                copy[k] == std::nextafter(m.body[k], -HUGE_VAL))
        << k;
    ASSERT_EQ(copy[k] * s, m.body[k] * s) << k;
    ASSERT_EQ(MerlRawFromValue(m.body[k] * s, static_cast<int>(k / kCells)), copy[k]);
  }
  // Random mantissas collide for roughly a tenth of the values (measured 8-14 % per channel).
  EXPECT_GT(changed, 0u);
  EXPECT_LT(changed, copy.size() / 4);
  RawMerl canonical;
  for (std::size_t k = 0; k < copy.size(); ++k) canonical.body[k] = copy[k];
  canonical.Write(dir / "canonical.binary");
  WriteMerl(ReadMerl(dir / "canonical.binary"), dir / "canonical2.binary");
  EXPECT_EQ(ReadBytes(dir / "canonical.binary"), ReadBytes(dir / "canonical2.binary"));
}

// A synthetic table (values not produced by a MERL read): masked cells come back masked, valid
// values within one ulp (the nearest raw), and a second round trip is exact.
TEST(MerlRoundTrip, SyntheticTableValuesComeBackWithinOneUlp) {
  ScratchDir dir;
  Table t = testing_io::RandomTable(Grid::Merl(), 3);
  for (std::size_t i = 0; i < kCells; i += 97) t.Value(i)[1] = std::nan("");  // masked garbage
  for (std::size_t i = 0; i < kCells; ++i) {
    if (i % 97 == 0) t.valid[i] = 0;
  }
  WriteMerl(t, dir / "s.binary");
  const Table r = ReadMerl(dir / "s.binary");
  EXPECT_EQ(r.valid, t.valid);
  for (std::size_t i = 0; i < kCells; ++i) {
    for (int c = 0; c < 3; ++c) {
      if (t.valid[i]) {
        ASSERT_LE(std::fabs(r.Value(i)[c] - t.Value(i)[c]), 0x1p-52 * t.Value(i)[c]) << i;
      } else {
        ASSERT_EQ(r.Value(i)[c], -kMerlChannelScale[c]) << i;  // written as raw -1
      }
    }
  }
  WriteMerl(r, dir / "s2.binary");
  const Table r2 = ReadMerl(dir / "s2.binary");
  EXPECT_EQ(r2.rgb, r.rgb);
  EXPECT_EQ(ReadBytes(dir / "s.binary"), ReadBytes(dir / "s2.binary"));
}

TEST(MerlWrite, RejectsOtherGridsAndUnstorableValidValues) {
  ScratchDir dir;
  const Table small = Table::Empty(Grid{45, 90, 180, ThetaHMapping::kSqrt});
  EXPECT_THROW(WriteMerl(small, dir / "x.binary"), InputError);
  const Table linear = Table::Empty(Grid{90, 90, 180, ThetaHMapping::kLinear});
  EXPECT_THROW(WriteMerl(linear, dir / "x.binary"), InputError);
  Table t = Table::Empty(Grid::Merl());
  t.valid[5] = 1;
  t.Value(5)[2] = -0.5;
  EXPECT_THAT([&] { WriteMerl(t, dir / "x.binary"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("cell 5")));
  t.Value(5)[2] = INFINITY;
  EXPECT_THROW(WriteMerl(t, dir / "x.binary"), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.binary"));
}

// ---- one test per rejected input (library level; the CLI tests check the printed line) ----

TEST(MerlErrors, WrongHeaderDimensionIsNamed) {
  ScratchDir dir;
  for (int k = 0; k < 3; ++k) {
    RawMerl m;
    m.dims[k] += 1;
    m.Write(dir / "bad.binary");
    const std::string expected[3] = {"header dimension 1 (theta_h bins) is 91, expected 90",
                                     "header dimension 2 (theta_d bins) is 91, expected 90",
                                     "header dimension 3 (phi_d bins) is 181, expected 180"};
    EXPECT_EQ(ErrorOf(dir / "bad.binary"), (dir / "bad.binary").string() + ": " + expected[k]);
  }
  // Same product, different dimensions: checking the product alone would accept this.
  RawMerl m;
  m.dims[0] = 180;
  m.dims[2] = 90;
  m.Write(dir / "swapped.binary");
  EXPECT_THAT(ErrorOf(dir / "swapped.binary"), HasSubstr("header dimension 1"));
}

TEST(MerlErrors, WrongSizeIsNamed) {
  ScratchDir dir;
  RawMerl m;
  m.Write(dir / "long.binary");
  std::ofstream(dir / "long.binary", std::ios::app | std::ios::binary) << "extra";
  EXPECT_EQ(ErrorOf(dir / "long.binary"),
            (dir / "long.binary").string() + ": file is 34992017 bytes, expected 34992012");
}

TEST(MerlErrors, TruncatedBodyIsNamed) {
  ScratchDir dir;
  RawMerl m;
  m.Write(dir / "short.binary", 1000);
  EXPECT_EQ(ErrorOf(dir / "short.binary"),
            (dir / "short.binary").string() + ": truncated: file is 1012 bytes, expected 34992012");
  testing_io::WriteBytes(dir / "tiny.binary", m.dims, 5);
  EXPECT_THAT(ErrorOf(dir / "tiny.binary"), HasSubstr("truncated header"));
}

TEST(MerlErrors, NaNAndInfAreNamedWithTheirCell) {
  ScratchDir dir;
  RawMerl m;
  m.body[2 * kCells + MerlIndex(10, 20, 30)] = std::nan("");
  m.Write(dir / "nan.binary");
  EXPECT_EQ(ErrorOf(dir / "nan.binary"),
            (dir / "nan.binary").string() +
                ": NaN at cell 165630 (theta_h 10, theta_d 20, phi_d 30), channel B");
  RawMerl inf;
  inf.body[0] = -INFINITY;
  inf.Write(dir / "inf.binary");
  EXPECT_THAT(ErrorOf(dir / "inf.binary"), HasSubstr("Inf at cell 0"));
}

TEST(MerlErrors, DirectoryAndMissingPathAreNamed) {
  ScratchDir dir;
  EXPECT_EQ(ErrorOf(dir.path()), dir.path().string() + ": is a directory");
  EXPECT_EQ(ErrorOf(dir / "nope.binary"), (dir / "nope.binary").string() + ": no such file");
}

}  // namespace
}  // namespace brdfit
