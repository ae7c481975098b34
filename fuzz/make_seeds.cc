// Writes the seed corpora fuzz/corpus/<reader>/ with brdfit's own writers (no third-party
// data): small valid files plus a few near-misses, so the fuzzer starts past the format checks.
// Also writes hand-crafted hostile files to fuzz/regressions/<reader>/crafted-* (inputs a
// fuzzer is unlikely to build: tiny files declaring huge shapes).
//   fuzz_make_seeds <repo>/fuzz
// Deterministic: the same sources give the same files.
#include <hdf5.h>
#include <zip.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <limits>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfTiledRgbaFile.h>

#include "core/table.h"
#include "fuzz/factor_checks.h"
#include "io/exr_texture.h"
#include "io/factor_io.h"
#include "io/fit_report.h"
#include "io/hdf5_table.h"
#include "io/merl.h"
#include "io/tensor_file.h"

namespace fs = std::filesystem;
using namespace brdfit;

namespace {

void WriteBytes(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string Raw(const void* p, std::size_t n) { return std::string(static_cast<const char*>(p), n); }

std::string MerlHeader(std::int32_t a = 90, std::int32_t b = 90, std::int32_t c = 180) {
  const std::int32_t d[3] = {a, b, c};
  return Raw(d, sizeof(d));
}

std::string Doubles(const std::vector<double>& v) { return Raw(v.data(), v.size() * sizeof(double)); }

// fuzz_merl input: mode byte (bit 0: expanded, bit 1: round trip), see fuzz/fuzz_merl.cc.
void MerlSeeds(const fs::path& dir) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  WriteBytes(dir / "raw-header-only", std::string(1, '\0') + MerlHeader());
  WriteBytes(dir / "raw-bad-dims", std::string(1, '\0') + MerlHeader(91, 90, 180) + Doubles({1, 2}));
  WriteBytes(dir / "raw-empty", std::string(1, '\0'));
  WriteBytes(dir / "expanded-valid", std::string(1, '\3') + MerlHeader() + '\0' + Doubles({0.5, 1.0, 2.0}));
  WriteBytes(dir / "expanded-masked", std::string(1, '\3') + MerlHeader() + '\0' + Doubles({0.5, -1.0, 3.0}));
  WriteBytes(dir / "expanded-zero", std::string(1, '\1') + MerlHeader() + '\0');
  WriteBytes(dir / "expanded-nan", std::string(1, '\1') + MerlHeader() + '\0' + Doubles({1.0, nan}));
  WriteBytes(dir / "expanded-inf", std::string(1, '\1') + MerlHeader() + '\0' + Doubles({-inf, 1.0}));
  WriteBytes(dir / "expanded-tiny", std::string(1, '\3') + MerlHeader() + '\0' + Doubles({5e-324, -0.0, 1e300}));
  WriteBytes(dir / "expanded-short", std::string(1, '\1') + MerlHeader() + '\xf7' + Doubles({1.0}));
  WriteBytes(dir / "expanded-long", std::string(1, '\1') + MerlHeader() + '\xf9' + Doubles({1.0}));
}

// fuzz_rgl_bsdf input: the .bsdf file itself. Small but valid RGB and spectral files (a GGX-like
// NDF, uniform projected area and VNDF, colours varying over the warped grid), one with the
// optional 'valid' mask, and one anisotropic (rejected: a seed for the error path).
std::vector<char> RglBsdfSeed(int rows, int n_theta, int n_phi, bool spectral, bool with_valid) {
  const double pi = 3.14159265358979323846;
  const auto r = static_cast<std::uint64_t>(rows), nt = static_cast<std::uint64_t>(n_theta),
             np = static_cast<std::uint64_t>(n_phi);
  std::vector<double> theta_i(nt), phi_i(np), ndf(2 * r), sigma(2 * r, 1.0);
  for (std::uint64_t i = 0; i < nt; ++i) theta_i[i] = 1.4 * static_cast<double>(i) / (nt - 1);
  for (std::uint64_t i = 0; i < np; ++i) phi_i[i] = np == 1 ? 0.0 : -pi + 2 * pi * i / (np - 1);
  for (std::uint64_t i = 0; i < 2 * r; ++i) ndf[i] = 1.0 / (0.1 + static_cast<double>(i % r));
  const std::uint64_t channels = spectral ? 4 : 3;
  std::vector<double> vndf(np * nt * r * r, 1.0), values(np * nt * channels * r * r);
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = 0.1 + 0.01 * static_cast<double>(i % 37);
  TensorFile f;
  const std::string d = "fuzz seed";
  f.fields.push_back(
      UInt8Field("description", {d.size()}, std::vector<std::uint8_t>(d.begin(), d.end())));
  f.fields.push_back(UInt8Field("jacobian", {1}, {1}));
  f.fields.push_back(Float32Field("theta_i", {nt}, theta_i));
  f.fields.push_back(Float32Field("phi_i", {np}, phi_i));
  f.fields.push_back(Float32Field("ndf", {2, r}, ndf));
  f.fields.push_back(Float32Field("sigma", {2, r}, sigma));
  f.fields.push_back(Float32Field("vndf", {np, nt, r, r}, vndf));
  f.fields.push_back(Float32Field("luminance", {np, nt, r, r}, vndf));
  if (spectral) {
    f.fields.push_back(Float32Field("wavelengths", {4}, {400, 500, 600, 700}));
    f.fields.push_back(Float32Field("spectra", {np, nt, channels, r, r}, values));
  } else {
    f.fields.push_back(Float32Field("rgb", {np, nt, channels, r, r}, values));
  }
  if (with_valid) {
    std::vector<std::uint8_t> valid(np * nt * r * r, 1);
    valid[valid.size() / 2] = 0;
    f.fields.push_back(UInt8Field("valid", {np, nt, r, r}, valid));
  }
  return SerializeTensorFile(f);
}

void RglBsdfSeeds(const fs::path& dir) {
  auto write = [&dir](const char* name, const std::vector<char>& b) {
    WriteBytes(dir / name, std::string(b.begin(), b.end()));
  };
  write("rgb-4x4", RglBsdfSeed(4, 3, 2, false, false));
  write("rgb-1phi-valid", RglBsdfSeed(3, 2, 1, false, true));
  write("spectral-3x3", RglBsdfSeed(3, 2, 1, true, false));
  write("anisotropic", RglBsdfSeed(2, 2, 3, false, false));
}

Table SmallTable(int nh, int nd, int np, ThetaHMapping m) {
  Grid g;
  g.n_theta_h = nh;
  g.n_theta_d = nd;
  g.n_phi_d = np;
  g.theta_h_mapping = m;
  Table t = Table::Empty(g);
  for (std::size_t i = 0; i < g.NumCells(); ++i) {
    t.valid[i] = i % 3 != 1;
    for (int c = 0; c < 3; ++c) t.rgb[3 * i + c] = 0.1 * (c + 1) + 0.01 * static_cast<double>(i);
  }
  t.provenance.source = "fuzz seed";
  t.provenance.generator = "fuzz_make_seeds";
  t.provenance.model = "lambert";
  t.provenance.parameters_json = R"({"kd":[0.1,0.2,0.3]})";
  t.provenance.seed = 7;
  t.provenance.noise = 0.01;
  t.provenance.missing_fraction = 0.25;
  return t;
}

void Hdf5Seeds(const fs::path& dir) {
  WriteHdf5Table(SmallTable(2, 3, 4, ThetaHMapping::kSqrt), dir / "sqrt-2x3x4.h5");
  WriteHdf5Table(SmallTable(3, 2, 2, ThetaHMapping::kLinear), dir / "linear-3x2x2.h5");
  Table one = SmallTable(1, 1, 1, ThetaHMapping::kSqrt);
  one.valid[0] = 1;
  WriteHdf5Table(one, dir / "single-cell.h5");
  Table holes = SmallTable(2, 2, 2, ThetaHMapping::kLinear);
  for (std::size_t i = 0; i < holes.valid.size(); i += 2) {
    holes.valid[i] = 0;
    holes.rgb[3 * i] = std::numeric_limits<double>::quiet_NaN();  // allowed in masked cells
  }
  WriteHdf5Table(holes, dir / "nan-in-masked.h5");
}

// ---- hand-crafted hostile HDF5 tables (C API: shapes the brdfit writer cannot produce) ----

// Group creation without timestamps: the same sources give the same bytes.
hid_t Group(hid_t parent, const char* name) {
  const hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
  H5Pset_obj_track_times(gcpl, 0);
  const hid_t g = H5Gcreate2(parent, name, H5P_DEFAULT, gcpl, H5P_DEFAULT);
  H5Pclose(gcpl);
  return g;
}

hid_t NoTimesDcpl() {
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_obj_track_times(dcpl, 0);
  return dcpl;
}

void StrAttr(hid_t obj, const char* name, const std::string& v) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, v.size() + 1);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, type, v.c_str());
  H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
}

template <class T>
void ScalarAttr(hid_t obj, const char* name, hid_t file_type, hid_t mem_type, T v) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(obj, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, mem_type, &v);
  H5Aclose(a);
  H5Sclose(space);
}

// A chunked dataset of the given shape with no chunk ever written: it costs a few hundred bytes
// in the file whatever its declared size (reads return the fill value).
void UnwrittenDataset(hid_t f, const char* name, hid_t type, const std::vector<hsize_t>& dims) {
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  std::vector<hsize_t> chunk(dims.size(), 1);
  chunk.back() = dims.back();
  H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data());
  H5Pset_obj_track_times(dcpl, 0);
  H5Dclose(H5Dcreate2(f, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT));
  H5Pclose(dcpl);
  H5Sclose(space);
}

// Axis datasets holding the true bin centres for the declared grid (so every check before the
// table allocation passes).
void Axes(hid_t f, const Grid& g) {
  const hid_t axes = Group(f, "axes");
  auto axis = [&](const char* name, int n, const char* mapping, auto at) {
    std::vector<double> c(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) c[i] = at(i + 0.5);
    const hsize_t dims[1] = {c.size()};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const hid_t dcpl = NoTimesDcpl();
    const hid_t ds = H5Dcreate2(axes, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    H5Pclose(dcpl);
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.data());
    StrAttr(ds, "mapping", mapping);
    H5Dclose(ds);
    H5Sclose(space);
  };
  axis("theta_h", g.n_theta_h, ToString(g.theta_h_mapping), [&](double u) { return g.ThetaHAt(u); });
  axis("theta_d", g.n_theta_d, "linear", [&](double u) { return g.ThetaDAt(u); });
  axis("phi_d", g.n_phi_d, "linear", [&](double u) { return g.PhiDAt(u); });
  H5Gclose(axes);
}

// A brdfit-table v1 file whose /values and /valid declare `dims` but store nothing.
void HugeDeclaredTable(const fs::path& path, const std::vector<hsize_t>& dims, bool with_axes) {
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  StrAttr(f, "format", kHdf5TableFormat);
  ScalarAttr(f, "format_version", H5T_STD_I32LE, H5T_NATIVE_INT32, std::int32_t{1});
  std::vector<hsize_t> vdims = dims;
  vdims.push_back(3);
  UnwrittenDataset(f, "values", H5T_IEEE_F64LE, vdims);
  UnwrittenDataset(f, "valid", H5T_STD_U8LE, dims);
  if (with_axes) {
    Grid g;
    g.n_theta_h = static_cast<int>(dims[0]);
    g.n_theta_d = static_cast<int>(dims[1]);
    g.n_phi_d = static_cast<int>(dims[2]);
    Axes(f, g);
  }
  H5Fclose(f);
}

// A file whose root attribute "format" is an array of variable-length strings.
void StringArrayAttr(const fs::path& path, hsize_t n) {
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  std::vector<const char*> v(n, "brdfit-table");
  const hid_t a = H5Acreate2(f, "format", type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, type, v.data());
  H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
  H5Fclose(f);
}

void Hdf5Crafted(const fs::path& dir) {
  // Reading it as one string made H5Aread store 64 pointers into one char* (stack overflow).
  StringArrayAttr(dir / "crafted-vlen-string-array-attr.h5", 64);
  // 2^30 cells (a 32 GB table in memory) declared by a few kB of file.
  HugeDeclaredTable(dir / "crafted-huge-declared-grid.h5", {1024, 1024, 1024}, true);
  // 2^26 cells (within the cap, 1.7 GB in memory) declared but never written.
  HugeDeclaredTable(dir / "crafted-unwritten-values.h5", {512, 512, 256}, true);
  // One axis of 2^31 bins: does not fit the grid's int.
  HugeDeclaredTable(dir / "crafted-axis-2pow31.h5", {hsize_t{1} << 31, 1, 1}, false);
  // Axis lengths whose product overflows 64 bits.
  HugeDeclaredTable(dir / "crafted-product-overflow.h5",
                    {hsize_t{1} << 31, hsize_t{1} << 31, hsize_t{1} << 31}, false);
}

// ---- NBRDF networks (layout of shared/data/README.md, weights made up here) ----------------

std::string ReadAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void Dense(hid_t f, int layer, hsize_t in, hsize_t out, float bias) {
  const std::string g1 = "dense_" + std::to_string(layer);
  const std::string g2 = g1 + "/" + g1;
  H5Gclose(Group(f, g1.c_str()));
  const hid_t g = Group(f, g2.c_str());
  auto write = [&](const char* name, std::vector<hsize_t> dims) {
    std::size_t n = 1;
    for (hsize_t d : dims) n *= d;
    std::vector<float> v(n);
    for (std::size_t i = 0; i < n; ++i) {
      v[i] = dims.size() == 1 ? bias : 0.3f * std::sin(1.7f * static_cast<float>(i + layer));
    }
    const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
    const hid_t dcpl = NoTimesDcpl();
    const hid_t ds = H5Dcreate2(g, name, H5T_IEEE_F32LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    H5Pclose(dcpl);
    H5Dwrite(ds, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Dclose(ds);
    H5Sclose(space);
  };
  write("kernel:0", {in, out});
  write("bias:0", {out});
  H5Gclose(g);
}

// A 6 -> h -> h -> 3 network as the NBRDF .h5 files store it; returns the file's bytes.
std::string NbrdfImage(const fs::path& tmp, hsize_t h, float out_bias) {
  const hid_t f = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  Dense(f, 1, 6, h, 0.1f);
  Dense(f, 2, h, h, 0.05f);
  Dense(f, 3, h, 3, out_bias);
  H5Fclose(f);
  std::string bytes = ReadAll(tmp);
  fs::remove(tmp);
  return bytes;
}

void Zip(const fs::path& path, const std::vector<std::pair<std::string, std::string>>& members) {
  int err = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  for (std::size_t i = 0; i < members.size(); ++i) {
    const auto& [name, data] = members[i];
    zip_source_t* src = zip_source_buffer(z, data.data(), data.size(), 0);
    const zip_int64_t idx = zip_file_add(z, name.c_str(), src, ZIP_FL_OVERWRITE);
    // Alternate stored and deflated members: both decoders get seeds.
    const auto u = static_cast<zip_uint64_t>(idx);
    zip_set_file_compression(z, u, i % 2 ? ZIP_CM_DEFLATE : ZIP_CM_STORE, 0);
    zip_file_set_mtime(z, u, 1600000000, 0);  // fixed: deterministic bytes
  }
  zip_close(z);
}

// fuzz_nbrdf input: mode byte (bit 0: member image, clear: whole archive), fuzz/fuzz_nbrdf.cc.
void NbrdfSeeds(const fs::path& dir) {
  const fs::path tmp = dir / ".tmp.h5";
  const std::string small = NbrdfImage(tmp, 4, -0.5f);
  const std::string wide = NbrdfImage(tmp, 21, 0.0f);
  const std::string overflow = NbrdfImage(tmp, 3, 800.0f);  // exp(y) overflows: InputError
  WriteBytes(dir / "member-small", std::string(1, '\1') + small);
  WriteBytes(dir / "member-21", std::string(1, '\1') + wide);
  WriteBytes(dir / "member-overflow", std::string(1, '\1') + overflow);
  const fs::path zip = dir / ".tmp.zip";
  Zip(zip, {{"merl_nbrdf/alpha.h5", small},
            {"merl_nbrdf/beta.h5", wide},
            {"merl_nbrdf/alpha.json", R"({"class_name": "Sequential"})"}});
  WriteBytes(dir / "archive-two", std::string(1, '\0') + ReadAll(zip));
  Zip(zip, {{"merl_nbrdf/solo.h5", small}});
  WriteBytes(dir / "archive-stored", std::string(1, '\0') + ReadAll(zip));
  fs::remove(zip);
}

// ---- factorization textures (OpenEXR) and sidecars -----------------------------------------

RgbImage Ramp(int w, int h) {
  RgbImage im = RgbImage::Filled(w, h, 0.0f);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      for (int c = 0; c < 3; ++c) im.At(i, j)[c] = 0.1f * static_cast<float>(i + 2 * j + c);
    }
  }
  return im;
}

// Half-float RGBA scan lines and tiles (the reader converts HALF to float), other codecs.
void HalfExr(const fs::path& path, int w, int h, Imf::Compression comp, bool tiled) {
  std::vector<Imf::Rgba> px(static_cast<std::size_t>(w) * h);
  for (std::size_t i = 0; i < px.size(); ++i) {
    px[i] = Imf::Rgba(0.01f * static_cast<float>(i), 0.5f, 2.0f, 1.0f);
  }
  if (tiled) {
    Imf::Header header(w, h);
    header.compression() = comp;
    Imf::TiledRgbaOutputFile f(path.c_str(), header, Imf::WRITE_RGBA, 2, 2, Imf::ONE_LEVEL);
    f.setFrameBuffer(px.data(), 1, w);
    f.writeTiles(0, f.numXTiles() - 1, 0, f.numYTiles() - 1);
  } else {
    Imf::RgbaOutputFile f(path.c_str(), w, h, Imf::WRITE_RGBA, 1, Imath::V2f(0, 0), 1,
                          Imf::INCREASING_Y, comp);
    f.setFrameBuffer(px.data(), 1, w);
    f.writePixels(h);
  }
}

// Two float RGB scan-line parts (the reader takes part 0).
void MultiPartExr(const fs::path& path) {
  std::vector<Imf::Header> headers;
  for (const char* name : {"first", "second"}) {
    Imf::Header h(2, 2);
    for (const char* c : {"R", "G", "B"}) h.channels().insert(c, Imf::Channel(Imf::FLOAT));
    h.setName(name);
    h.setType(Imf::SCANLINEIMAGE);
    headers.push_back(h);
  }
  Imf::MultiPartOutputFile file(path.c_str(), headers.data(), static_cast<int>(headers.size()));
  std::vector<float> px(2 * 2 * 3, 0.75f);
  for (int part = 0; part < 2; ++part) {
    Imf::OutputPart out(file, part);
    Imf::FrameBuffer fb;
    for (int c = 0; c < 3; ++c) {
      static const char* const kRgb[3] = {"R", "G", "B"};
      fb.insert(kRgb[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data() + c), 12, 24));
    }
    out.setFrameBuffer(fb);
    out.writePixels(2);
  }
}

void ExrSeeds(const fs::path& dir) {
  WriteRgbExr(dir / "one-pixel.exr", RgbImage::Filled(1, 1, 0.5f), {});
  WriteRgbExr(dir / "ramp-5x3-attrs.exr", Ramp(5, 3),
              {{"brdfit:factor", "p"}, {"brdfit:parameterization", "pq"}, {"note", ""}});
  RgbImage odd = Ramp(2, 2);
  odd.At(0, 0)[0] = std::numeric_limits<float>::quiet_NaN();
  odd.At(1, 0)[1] = std::numeric_limits<float>::infinity();
  odd.At(1, 1)[2] = -0.0f;
  WriteRgbExr(dir / "nan-inf-2x2.exr", odd, {});
  HalfExr(dir / "half-piz-4x3.exr", 4, 3, Imf::PIZ_COMPRESSION, false);
  HalfExr(dir / "half-rle-3x3.exr", 3, 3, Imf::RLE_COMPRESSION, false);
  HalfExr(dir / "half-none-tiled-5x4.exr", 5, 4, Imf::NO_COMPRESSION, true);
  MultiPartExr(dir / "multipart-2x2.exr");
}

// A float RGB scan-line file whose header declares w x h pixels and which stores none (the
// writer is closed before any line is written): 16 kB declaring 32768 x 32768.
void EmptyExr(const fs::path& path, int w, int h) {
  Imf::Header header(w, h);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
  Imf::OutputFile f(path.c_str(), header);
}

void ExrCrafted(const fs::path& dir) { EmptyExr(dir / "crafted-32768x32768-no-pixels.exr", 32768, 32768); }

void SidecarCrafted(const fs::path& dir) {
  WriteBytes(dir / "crafted-format-not-string.json", R"({"format": 1})");
  WriteBytes(dir / "crafted-textures-not-object.json",
             R"({"format": "brdfit-factorization", "format_version": 1, "parameterization": "pq",
                 "textures": [1, 2]})");
  WriteBytes(dir / "crafted-absolute-file.json",
             R"({"format": "brdfit-factorization", "format_version": 1, "parameterization": "pq",
                 "textures": {"p": {"file": "/dev/zero", "width": 1, "height": 1},
                              "q": {"file": "/proc/self/mem", "width": 1, "height": 1}}})");
}

void SidecarSeeds(const fs::path& dir) {
  // The fuzz_factor_sidecar harness writes, with parameterization "pq", p (3 x 2), q (2 x 4),
  // p2 (2 x 2) and q2 (3 x 3) as f.p.exr, f.q.exr, f.p2.exr, f.q2.exr; these sidecars are what
  // WriteFactorFiles writes for them at rank 2 (with a diffuse value) and at rank 1.
  const fs::path tmp = dir / ".tmp";
  fs::create_directories(tmp);
  FactorFiles f;
  f.sidecar = {{"parameterization", "pq"},
               {"formula", "f = d + p(wi) q(wh) p(wo) + p2(wi) q2(wh) p2(wo)"},
               {"statistics", {{"cells", 12}, {"rms", 0.25}}}};
  f.diffuse = {0.01, 0.02, 0.03};
  f.terms.resize(2);
  f.terms[0].p.image = RgbImage::Filled(3, 2, 0.25f);
  f.terms[0].q.image = RgbImage::Filled(2, 4, 2.0f);
  f.terms[1].p.image = RgbImage::Filled(2, 2, 0.5f);
  f.terms[1].q.image = RgbImage::Filled(3, 3, 1.0f);
  WriteFactorFiles(FactorFilePaths(tmp, "f", 2), f);
  const std::string valid = ReadAll(tmp / "f.factor.json");
  f.terms.resize(1);
  f.diffuse = {0, 0, 0};
  WriteFactorFiles(FactorFilePaths(tmp, "f", 1), f);
  const std::string rank1 = ReadAll(tmp / "f.factor.json");
  fs::remove_all(tmp);
  WriteBytes(dir / "valid.json", valid);
  WriteBytes(dir / "valid-rank-1.json", rank1);
  nlohmann::json j = nlohmann::json::parse(rank1);  // as version 1 wrote it
  j["format_version"] = 1;
  j.erase("rank");
  j.erase("diffuse");
  j.erase("kd");
  WriteBytes(dir / "version-1.json", j.dump());
  j = nlohmann::json::parse(valid);
  j["textures"]["q"]["width"] = 3;
  WriteBytes(dir / "size-mismatch.json", j.dump());
  j = nlohmann::json::parse(valid);
  j["textures"]["p"]["file"] = "f.q.exr";
  WriteBytes(dir / "swapped-factor.json", j.dump());
  j = nlohmann::json::parse(valid);
  j["rank"] = 3;
  WriteBytes(dir / "rank-beyond-textures.json", j.dump());
  j = nlohmann::json::parse(valid);
  j["diffuse"] = {0.01, -0.02, 0.03};
  WriteBytes(dir / "negative-diffuse.json", j.dump());
  j = nlohmann::json::parse(valid);
  j["format_version"] = 3;
  WriteBytes(dir / "version-3.json", j.dump());
  WriteBytes(dir / "not-object.json", "[1, 2, 3]");
}

// ---- fit reports --------------------------------------------------------------------------

FitReportEntry ReportEntry(const std::string& source, const std::string& model, bool failed) {
  FitReportEntry e;
  e.source = source;
  e.material = fs::path(source).stem().string();
  e.options = R"({"fit":{"loss":"log","max_iterations":100},"samples":{"cutoff_deg":80}})";
  FitResult& r = e.result;
  r.model = model;
  r.param_names = {"lambert.kd_r", "lambert.kd_g", "lambert.kd_b", "ggx.ks_r", "ggx.ks_g",
                   "ggx.ks_b",     "ggx.alpha"};
  r.params = {0.3, 0.25, 0.2, 0.5, 0.5, 0.5, 0.12};
  r.at_bound = {false, false, false, false, false, false, true};
  r.status = failed ? FitStatus::kFailed : FitStatus::kConverged;
  r.message = failed ? "no usable cells" : "";
  r.termination = failed ? "" : "CONVERGENCE";
  r.iterations = failed ? 0 : 17;
  r.starts = 1;
  r.init_cost = 1.5;
  r.final_cost = 0.25;
  r.fit_samples = 1000;
  r.fit_cells = 2000;
  r.metrics.ok = !failed;
  r.metrics.problem = failed ? "no samples" : "";
  r.metrics.log_rmse = 0.05;
  r.metrics.cbrt_rmse = 0.04;
  r.metrics.rel_l2 = 0.1;
  r.metrics.cells = 2000;
  r.metrics.total_weight = 3.5;
  r.metrics.weighting = "bin-measure";
  r.metrics.cutoff_deg = 80;
  r.metrics.worst.cell = 1234;
  r.metrics.worst.angles = {0.1, 0.2, 0.3};
  r.metrics.worst.measured = {1, 2, 3};
  r.metrics.worst.predicted = {1.5, 2.5, 3.5};
  r.times.solve = 12.5;
  return e;
}

void FitReportSeeds(const fs::path& dir) {
  WriteFitReport({ReportEntry("mats/gold.binary", "lambert+ggx", false),
                  ReportEntry("mats/felt.h5", "lambert+ggx", true)},
                 dir / "two-entries.h5", true);
  WriteFitReport({ReportEntry("t.binary", "lambert+ggx", false)}, dir / "no-timings.h5", false);
  WriteFitReport({}, dir / "empty.h5", true);
  // A factorization among the candidates (io/fit_report.h): no parameters, its group.
  FitReportEntry f = ReportEntry("t.binary", kFactorizationModel, false);
  f.result.param_names.clear();
  f.result.params.clear();
  f.result.at_bound.clear();
  f.factorization = FactorizationRef{"mccool r2", "fits.factors/t.factor.json", 196608, 49152};
  WriteFitReport({ReportEntry("t.binary", "lambert+ggx", false), f}, dir / "factorization.h5",
                 false);
}

void FitReportCrafted(const fs::path& dir) {
  // The writer stores the options string as given; a report from elsewhere may hold anything.
  FitReportEntry e = ReportEntry("t.binary", "lambert+ggx", false);
  e.options = "{not json";
  WriteFitReport({e}, dir / "crafted-options-not-json.h5", false);
  e = ReportEntry("t.binary", "lambert+ggx", false);
  e.result.param_names = {"a", "a", "b", "c", "d", "e", "f"};  // duplicate names
  WriteFitReport({e}, dir / "crafted-duplicate-param-names.h5", false);
}

}  // namespace

// fuzz_factor_files input: byte 0 picks the file (0 sidecar, 1 p, 2 q, 3 p2, 4 q2) the rest
// replaces beside the valid factorization of fuzz/factor_checks.h (fuzz/fuzz_factor_files.cc).
void FactorFilesSeeds(const fs::path& dir) {
  const fs::path tmp = dir / ".valid";
  fs::create_directories(tmp);
  const FactorPaths paths = FactorFilePaths(tmp, "h", 2);
  WriteFactorFiles(paths, fuzz::ValidFactorFiles());
  auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string sidecar = bytes(paths.json), p = bytes(paths.terms[0].p),
                    q = bytes(paths.terms[0].q), p2 = bytes(paths.terms[1].p),
                    q2 = bytes(paths.terms[1].q);
  fs::remove_all(tmp);
  WriteBytes(dir / "valid-sidecar", std::string(1, '\0') + sidecar);
  WriteBytes(dir / "valid-p", std::string(1, '\1') + p);
  WriteBytes(dir / "valid-q", std::string(1, '\2') + q);
  WriteBytes(dir / "valid-p2", std::string(1, '\3') + p2);
  WriteBytes(dir / "valid-q2", std::string(1, '\4') + q2);
  WriteBytes(dir / "q-as-p", std::string(1, '\1') + q);    // another size and factor name
  WriteBytes(dir / "p-as-p2", std::string(1, '\3') + p);   // p's factor name as p2
  WriteBytes(dir / "p-truncated", std::string(1, '\1') + p.substr(0, p.size() / 2));
  WriteBytes(dir / "p-empty", std::string(1, '\1'));
}

// A NaN texel in h.q.exr: was read, and broke fuzz_factor_files' round trip (NaN != NaN).
void FactorFilesCrafted(const fs::path& dir) {
  const fs::path tmp = dir / ".nan";
  fs::create_directories(tmp);
  FactorFiles f = fuzz::ValidFactorFiles();
  f.terms[0].q.image.At(1, 2)[0] = std::numeric_limits<float>::quiet_NaN();
  const FactorPaths paths = FactorFilePaths(tmp, "h", 2);
  WriteFactorFiles(paths, f);
  std::ifstream in(paths.terms[0].q, std::ios::binary);
  const std::string q(std::istreambuf_iterator<char>(in), {});
  fs::remove_all(tmp);
  WriteBytes(dir / "crafted-nan-texel-q", std::string(1, '\2') + q);
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_make_seeds <repo>/fuzz\n";
    return 2;
  }
  const fs::path corpus = fs::path(argv[1]) / "corpus";
  const fs::path regressions = fs::path(argv[1]) / "regressions";
  for (const char* d : {"merl", "hdf5_table", "nbrdf", "exr", "factor_sidecar", "fit_report",
                        "factor_files", "rgl_bsdf"}) {
    fs::create_directories(corpus / d);
    fs::create_directories(regressions / d);
  }
  MerlSeeds(corpus / "merl");
  RglBsdfSeeds(corpus / "rgl_bsdf");
  Hdf5Seeds(corpus / "hdf5_table");
  Hdf5Crafted(regressions / "hdf5_table");
  NbrdfSeeds(corpus / "nbrdf");
  ExrSeeds(corpus / "exr");
  SidecarSeeds(corpus / "factor_sidecar");
  FitReportSeeds(corpus / "fit_report");
  FactorFilesSeeds(corpus / "factor_files");
  FactorFilesCrafted(regressions / "factor_files");
  FitReportCrafted(regressions / "fit_report");
  ExrCrafted(regressions / "exr");
  SidecarCrafted(regressions / "factor_sidecar");
  std::cout << "seeds written to " << corpus << ", crafted inputs to " << regressions << "\n";
  return 0;
}
