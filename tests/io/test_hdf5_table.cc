// brdfit HDF5 tables (io/hdf5_table.h, docs/formats.md): exact round trips, deterministic
// bytes, and a named error for each malformed file.
#include <H5Cpp.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>

#include "core/error.h"
#include "io/hdf5_table.h"
#include "io_test_util.h"

namespace brdfit {
namespace {

using ::testing::HasSubstr;
using testing_io::ScratchDir;

Table ExampleTable(const Grid& g) {
  Table t = testing_io::RandomTable(g, 42);
  t.provenance.source = "synthetic";
  t.provenance.generator = "brdfit synth";
  t.provenance.model = "lambert+ggx";
  t.provenance.parameters_json = R"({"ggx.alpha":0.1,"lambert.kd_r":0.5})";
  t.provenance.seed = 0xFEDCBA9876543210ull;
  t.provenance.noise = 0.05;
  t.provenance.missing_fraction = 0.3;
  return t;
}

std::string ErrorOf(const std::filesystem::path& p) {
  try {
    ReadHdf5Table(p);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Hdf5Table, WriteReadIsExactOnAnyGridAndMapping) {
  ScratchDir dir;
  for (const Grid& g :
       {Grid{7, 5, 11, ThetaHMapping::kLinear}, Grid{16, 9, 32, ThetaHMapping::kSqrt},
        Grid{1, 1, 1, ThetaHMapping::kSqrt}}) {
    const Table t = ExampleTable(g);
    WriteHdf5Table(t, dir / "t.h5");
    const Table r = ReadHdf5Table(dir / "t.h5");
    EXPECT_EQ(r, t);  // grid, every double, mask, provenance
  }
}

TEST(Hdf5Table, InvalidCellsKeepWhateverTheyHeldIncludingNaN) {
  ScratchDir dir;
  Table t = ExampleTable(Grid{4, 4, 8, ThetaHMapping::kSqrt});
  t.valid[3] = 0;
  t.Value(3)[0] = std::nan("");
  t.Value(3)[1] = -1.0;
  WriteHdf5Table(t, dir / "t.h5");
  const Table r = ReadHdf5Table(dir / "t.h5");
  EXPECT_EQ(std::memcmp(r.rgb.data(), t.rgb.data(), t.rgb.size() * sizeof(double)), 0);
  EXPECT_EQ(r.valid, t.valid);
}

TEST(Hdf5Table, EmptyAndNonAsciiProvenanceStrings) {
  ScratchDir dir;
  Table t = ExampleTable(Grid{2, 2, 2, ThetaHMapping::kLinear});
  t.provenance.model = "";
  t.provenance.source = "mesures/peinture-dorée.binary";
  WriteHdf5Table(t, dir / "t.h5");
  EXPECT_EQ(ReadHdf5Table(dir / "t.h5").provenance, t.provenance);
}

TEST(Hdf5Table, FullMerlGridRoundTripIsExact) {
  ScratchDir dir;
  const Table t = ExampleTable(Grid::Merl());
  WriteHdf5Table(t, dir / "t.h5");
  EXPECT_EQ(ReadHdf5Table(dir / "t.h5"), t);
}

// HDF5 stores object timestamps by default; brdfit turns them off so that equal tables give
// equal files (synth: same seed -> same bytes). The files are written more than a second apart.
TEST(Hdf5Table, SameTableGivesSameBytesAtDifferentTimes) {
  ScratchDir dir;
  const Table t = ExampleTable(Grid{6, 6, 12, ThetaHMapping::kSqrt});
  WriteHdf5Table(t, dir / "a.h5");
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  WriteHdf5Table(t, dir / "b.h5");
  EXPECT_EQ(testing_io::ReadBytes(dir / "a.h5"), testing_io::ReadBytes(dir / "b.h5"));
}

TEST(Hdf5Table, AxesDescribeTheCellCentres) {
  ScratchDir dir;
  const Grid g{10, 6, 12, ThetaHMapping::kSqrt};
  WriteHdf5Table(ExampleTable(g), dir / "t.h5");
  H5::H5File f((dir / "t.h5").string(), H5F_ACC_RDONLY);
  std::vector<double> th(10);
  H5::DataSet ds = f.openDataSet("axes/theta_h");
  ds.read(th.data(), H5::PredType::NATIVE_DOUBLE);
  // MERL mapping (BRDFRead.cpp): bin i covers [(i/n)^2, ((i+1)/n)^2] * 90 deg; centre at
  // index coordinate i + 0.5.
  for (int i = 0; i < 10; ++i) EXPECT_DOUBLE_EQ(th[i], kPi / 2 * std::pow((i + 0.5) / 10, 2));
  std::string mapping;
  ds.openAttribute("mapping").read(ds.openAttribute("mapping").getStrType(), mapping);
  EXPECT_EQ(mapping, "sqrt");
}

// ---- malformed files ------------------------------------------------------------------

class Hdf5TableErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    WriteHdf5Table(ExampleTable(Grid{4, 3, 6, ThetaHMapping::kLinear}), path_);
  }
  H5::H5File Open() { return H5::H5File(path_.string(), H5F_ACC_RDWR); }
  ScratchDir dir_;
  std::filesystem::path path_ = dir_ / "t.h5";
};

TEST_F(Hdf5TableErrors, NotAnHdf5File) {
  std::ofstream(path_) << "hello";
  EXPECT_EQ(ErrorOf(path_), path_.string() + ": not an HDF5 file");
}

TEST_F(Hdf5TableErrors, MissingValues) {
  Open().unlink("values");
  EXPECT_EQ(ErrorOf(path_), path_.string() + ": missing dataset /values");
}

TEST_F(Hdf5TableErrors, NotABrdfitTable) {
  Open().removeAttr("format");
  EXPECT_EQ(ErrorOf(path_), path_.string() + ": missing attribute 'format' on /");
}

TEST_F(Hdf5TableErrors, UnsupportedVersion) {
  H5::Attribute a = Open().openAttribute("format_version");
  const std::int32_t v = 7;
  a.write(H5::PredType::NATIVE_INT32, &v);
  a.close();
  EXPECT_THAT(ErrorOf(path_), HasSubstr("format_version 7 is not supported"));
}

TEST_F(Hdf5TableErrors, MaskShapeMismatch) {
  H5::H5File f = Open();
  f.unlink("valid");
  const hsize_t dims[3] = {4, 3, 5};
  f.createDataSet("valid", H5::PredType::STD_U8LE, H5::DataSpace(3, dims));
  f.close();
  EXPECT_THAT(ErrorOf(path_), HasSubstr("/valid must have shape"));
}

TEST_F(Hdf5TableErrors, AxisThatIsNotTheGridsCentres) {
  H5::DataSet ds = Open().openDataSet("axes/theta_d");
  std::vector<double> c(3, 0.25);
  ds.write(c.data(), H5::PredType::NATIVE_DOUBLE);
  ds.close();
  EXPECT_THAT(ErrorOf(path_), HasSubstr("/axes/theta_d[0] is 0.25, expected the bin centre"));
}

TEST_F(Hdf5TableErrors, NaNInAValidCell) {
  Table t = ExampleTable(Grid{4, 3, 6, ThetaHMapping::kLinear});
  t.valid[5] = 1;
  t.Value(5)[1] = std::nan("");
  WriteHdf5Table(t, path_);
  EXPECT_EQ(ErrorOf(path_),
            path_.string() + ": NaN at valid cell 5 (theta_h 0, theta_d 0, phi_d 5), channel G");
}

TEST_F(Hdf5TableErrors, MaskValueOtherThanZeroOrOne) {
  Table t = ExampleTable(Grid{4, 3, 6, ThetaHMapping::kLinear});
  t.valid[2] = 7;
  WriteHdf5Table(t, path_);
  EXPECT_THAT(ErrorOf(path_), HasSubstr("/valid[2] is 7, expected 0 or 1"));
}

// /values and /valid rewritten as chunked datasets (chunk: one theta_h row), gzip-compressed
// when `deflate`; with `skip_last_chunk` the last chunk of /values is never written.
void RechunkTable(const std::filesystem::path& path, const Table& t, bool deflate,
                  bool skip_last_chunk) {
  H5::H5File f(path.string(), H5F_ACC_RDWR);
  f.unlink("values");
  f.unlink("valid");
  const Grid& g = t.grid;
  const hsize_t vdims[4] = {hsize_t(g.n_theta_h), hsize_t(g.n_theta_d), hsize_t(g.n_phi_d), 3};
  const hsize_t vchunk[4] = {1, vdims[1], vdims[2], 3};
  H5::DSetCreatPropList vp;
  vp.setChunk(4, vchunk);
  if (deflate) vp.setDeflate(6);  // H5Pset_deflate: what h5py's compression="gzip" writes
  H5::DataSet values =
      f.createDataSet("values", H5::PredType::IEEE_F64LE, H5::DataSpace(4, vdims), vp);
  if (skip_last_chunk) {
    H5::DataSpace file_space = values.getSpace();
    const hsize_t start[4] = {0, 0, 0, 0}, count[4] = {vdims[0] - 1, vdims[1], vdims[2], 3};
    file_space.selectHyperslab(H5S_SELECT_SET, count, start);
    H5::DataSpace mem(4, count);
    values.write(t.rgb.data(), H5::PredType::NATIVE_DOUBLE, mem, file_space);
  } else {
    values.write(t.rgb.data(), H5::PredType::NATIVE_DOUBLE);
  }
  H5::DSetCreatPropList mp;
  mp.setChunk(3, vchunk);
  if (deflate) mp.setDeflate(6);
  H5::DataSet valid =
      f.createDataSet("valid", H5::PredType::STD_U8LE, H5::DataSpace(3, vdims), mp);
  valid.write(t.valid.data(), H5::PredType::NATIVE_UINT8);
}

// Issue 14 item 9: chunked, compressed storage was taken for missing data ("declares data that
// the file does not store": libhdf5 calls it partly allocated).
TEST_F(Hdf5TableErrors, GzipCompressedTableLoadsExactly) {
  const Table t = ExampleTable(Grid{4, 3, 6, ThetaHMapping::kLinear});
  for (const bool deflate : {true, false}) {
    RechunkTable(path_, t, deflate, false);
    {
      H5::H5File f(path_.string(), H5F_ACC_RDONLY);
      ASSERT_EQ(f.openDataSet("values").getCreatePlist().getNfilters(), deflate ? 1 : 0);
    }
    Table back;
    ASSERT_NO_THROW(back = ReadHdf5Table(path_)) << ErrorOf(path_);
    EXPECT_EQ(back.valid, t.valid);
    for (std::size_t i = 0; i < t.rgb.size(); ++i) {
      if (t.valid[i / 3]) {
        ASSERT_EQ(back.rgb[i], t.rgb[i]) << i;
      }
    }
  }
}

TEST_F(Hdf5TableErrors, ChunkedTableWithAnUnwrittenChunkIsRefused) {
  const Table t = ExampleTable(Grid{4, 3, 6, ThetaHMapping::kLinear});
  RechunkTable(path_, t, true, true);
  EXPECT_EQ(ErrorOf(path_), path_.string() +
                                ": dataset /values declares data that the file does not store "
                                "(3 of 4 chunks written)");
}

TEST_F(Hdf5TableErrors, DirectoryAndMissingPath) {
  EXPECT_EQ(ErrorOf(dir_.path()), dir_.path().string() + ": is a directory");
  EXPECT_EQ(ErrorOf(dir_ / "none.h5"), (dir_ / "none.h5").string() + ": no such file");
}

}  // namespace
}  // namespace brdfit
