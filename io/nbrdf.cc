#include "io/nbrdf.h"

#include <H5Cpp.h>
#include <fmt/core.h>
#include <hdf5.h>
#include <zip.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/error.h"
#include "core/suggest.h"
#include "io/hdf5_util.h"
#include "io/input_file.h"

namespace brdfit {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMemberDir = "merl_nbrdf/";
constexpr const char* kMemberExt = ".h5";
// Bounds on what an archive may declare, checked before allocating (fuzz_nbrdf): the networks
// of the distribution are 6-21-21-3 and their members ~5 kB.
constexpr zip_uint64_t kMaxMemberBytes = zip_uint64_t{64} << 20;
constexpr hsize_t kMaxHiddenUnits = 1024;

struct ZipCloser {
  void operator()(zip_t* z) const { zip_discard(z); }  // read-only: nothing to write back
};
using ZipPtr = std::unique_ptr<zip_t, ZipCloser>;

ZipPtr OpenZip(const fs::path& zip) {
  CheckInputFile(zip);
  int err = 0;
  zip_t* z = zip_open(zip.c_str(), ZIP_RDONLY, &err);
  if (!z) {
    zip_error_t e;
    zip_error_init_with_code(&e, err);
    const std::string msg = zip_error_strerror(&e);
    zip_error_fini(&e);
    throw InputError(zip, "cannot open zip archive: " + msg);
  }
  return ZipPtr(z);
}

std::vector<std::string> Materials(const fs::path& path, zip_t* z) {
  std::vector<std::string> out;
  const zip_int64_t n = zip_get_num_entries(z, 0);
  const std::string dir = kMemberDir, ext = kMemberExt;
  for (zip_int64_t i = 0; i < n; ++i) {
    const char* name = zip_get_name(z, static_cast<zip_uint64_t>(i), 0);
    if (!name) throw InputError(path, "cannot read the archive's directory");
    const std::string s = name;
    if (s.size() > dir.size() + ext.size() && s.starts_with(dir) && s.ends_with(ext)) {
      out.push_back(s.substr(dir.size(), s.size() - dir.size() - ext.size()));
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<char> ReadMember(const fs::path& path, zip_t* z, const std::string& member) {
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat(z, member.c_str(), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE)) {
    throw InputError(path, "cannot stat member " + member);
  }
  if (st.size > kMaxMemberBytes) {
    throw InputError(path, fmt::format("member {} declares {} bytes (at most {})", member,
                                       st.size, kMaxMemberBytes));
  }
  std::unique_ptr<zip_file_t, decltype(&zip_fclose)> f(zip_fopen(z, member.c_str(), 0),
                                                       &zip_fclose);
  if (!f) throw InputError(path, "cannot open member " + member + ": " + zip_strerror(z));
  std::vector<char> buf(st.size);
  zip_uint64_t got = 0;
  while (got < st.size) {
    const zip_int64_t n = zip_fread(f.get(), buf.data() + got, st.size - got);
    if (n <= 0) throw InputError(path, "cannot decompress member " + member);
    got += static_cast<zip_uint64_t>(n);
  }
  return buf;
}

// Reads dataset `name` ([rows][cols] or [cols]) as doubles in row-major order.
Eigen::MatrixXd ReadWeights(const hdf5::Reader& in, const H5::H5File& f, const std::string& name,
                            hsize_t rows, hsize_t cols) {
  std::vector<hsize_t> dims;
  const H5::DataSet ds = in.Dataset(f, "/", name, H5T_FLOAT, &dims);
  const bool ok = (rows == 0) ? (dims.size() == 1 && dims[0] == cols)
                              : (dims.size() == 2 && dims[0] == rows && dims[1] == cols);
  if (!ok) {
    in.Fail(
        fmt::format("dataset /{} has the wrong shape (expected float [{}][{}])", name, rows, cols));
  }
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m(
      std::max<hsize_t>(rows, 1), cols);
  const std::vector<double> v = in.ReadFinite(ds, "dataset /" + name);
  std::copy(v.begin(), v.end(), m.data());
  return m;
}

// Whether every group on `path` exists: H5Lexists fails (rather than saying no) when an
// intermediate group is missing ("H5Lexists failed" for an archive member that is some other
// HDF5 file).
bool PathExists(const H5::H5File& f, const std::string& path) {
  for (std::size_t at = path.find('/'); ; at = path.find('/', at + 1)) {
    if (!f.nameExists(path.substr(0, at))) return false;
    if (at == std::string::npos) return true;
  }
}

hsize_t Columns(const H5::H5File& f, const std::string& name) {
  if (!f.nameExists(name)) return 0;
  const H5::DataSpace space = f.openDataSet(name).getSpace();
  if (space.getSimpleExtentNdims() != 2) return 0;
  hsize_t dims[2];
  space.getSimpleExtentDims(dims);
  return dims[1];
}

}  // namespace

std::vector<std::string> ListNbrdfMaterials(const fs::path& zip) {
  ZipPtr z = OpenZip(zip);
  return Materials(zip, z.get());
}

NbrdfNetwork ReadNbrdf(const fs::path& zip, const std::string& material) {
  ZipPtr z = OpenZip(zip);
  const std::string member = kMemberDir + material + kMemberExt;
  if (zip_name_locate(z.get(), member.c_str(), 0) < 0) {
    const auto names = Materials(zip, z.get());
    if (const std::string hint = DidYouMean(material, names); !hint.empty()) {
      throw InputError(zip, fmt::format("no material '{}': {} (brdfit synth --list-nbrdf lists "
                                        "the archive's {})",
                                        material, hint, names.size()));
    }
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError(zip, fmt::format("no material '{}' (the archive has {}: {})", material,
                                      names.size(), list));
  }
  std::vector<char> image = ReadMember(zip, z.get(), member);

  hdf5::Quiet();
  const hdf5::Reader in(zip, member + ": ");
  NbrdfNetwork net;
  net.material = material;
  net.source = zip.string() + ":" + member;
  try {
    // HDF5 core driver on a copy of the in-memory image, no backing store: nothing touches disk.
    H5::FileAccPropList fapl;
    H5Pset_fapl_core(fapl.getId(), 1 << 16, /*backing_store=*/0);
    H5Pset_file_image(fapl.getId(), image.data(), image.size());
    // The core driver refuses a name that exists on disk; "<zip>/<member>" never does (the zip
    // is a file, not a folder).
    H5::H5File f((zip / member).string(), H5F_ACC_RDONLY, H5::FileCreatPropList::DEFAULT, fapl);
    const std::string l1 = "dense_1/dense_1/", l2 = "dense_2/dense_2/", l3 = "dense_3/dense_3/";
    // Another HDF5 file (a table, say) stored as a member: no first layer at all.
    if (!PathExists(f, l1 + "kernel:0")) {
      throw InputError(zip, fmt::format("{}: not an NBRDF network (no dataset /{}kernel:0; "
                                        "expected the Keras weights dense_1 to dense_3)",
                                        member, l1));
    }
    const hsize_t h1 = Columns(f, l1 + "kernel:0"), h2 = Columns(f, l2 + "kernel:0");
    if (h1 > kMaxHiddenUnits || h2 > kMaxHiddenUnits) {
      throw InputError(zip, fmt::format("{}: hidden layers of {} and {} units (at most {})", member,
                                        h1, h2, kMaxHiddenUnits));
    }
    net.k1 = ReadWeights(in, f, l1 + "kernel:0", 6, h1);
    net.b1 = ReadWeights(in, f, l1 + "bias:0", 0, h1);
    net.k2 = ReadWeights(in, f, l2 + "kernel:0", h1, h2);
    net.b2 = ReadWeights(in, f, l2 + "bias:0", 0, h2);
    net.k3 = ReadWeights(in, f, l3 + "kernel:0", h2, 3);
    net.b3 = ReadWeights(in, f, l3 + "bias:0", 0, 3);
    if (h1 == 0 || h2 == 0) throw InputError(zip, member + ": empty hidden layer");
  } catch (const H5::Exception& e) {
    throw InputError(zip, member + ": " + hdf5::Describe(e));
  }
  return net;
}

}  // namespace brdfit
