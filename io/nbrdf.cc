#include "io/nbrdf.h"

#include <H5Cpp.h>
#include <fmt/core.h>
#include <hdf5.h>
#include <zip.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <thread>

#include "core/error.h"
#include "core/suggest.h"
#include "io/hdf5_util.h"
#include "io/input_file.h"
#include "io/nbrdf_forward.h"

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

std::array<double, 3> EvalNbrdf(const NbrdfNetwork& net, const HalfDiffAngles& a) {
  Eigen::RowVectorXd x(6);
  x << std::sin(a.theta_h), 0.0, std::cos(a.theta_h), std::sin(a.theta_d) * std::cos(a.phi_d),
      std::sin(a.theta_d) * std::sin(a.phi_d), std::cos(a.theta_d);
  const Eigen::RowVectorXd h1 = (x * net.k1 + net.b1).cwiseMax(0.0);
  const Eigen::RowVectorXd h2 = (h1 * net.k2 + net.b2).cwiseMax(0.0);
  const Eigen::RowVectorXd y = h2 * net.k3 + net.b3;
  return {std::expm1(y[0]), std::expm1(y[1]), std::expm1(y[2])};
}

NbrdfTabulation TabulateNbrdf(const NbrdfNetwork& net, const Grid& grid, int threads) {
  NbrdfTabulation out;
  out.table = Table::Empty(grid);
  Table& t = out.table;
  const int nd = grid.n_theta_d, np = grid.n_phi_d;
  const Eigen::Index rows = static_cast<Eigen::Index>(nd) * np;

  // The difference-vector part of x is the same in every theta_h slice: fold it into the first
  // layer once. P = [sin td cos pd, sin td sin pd, cos td] K1[3:6] + b1, one row per (id, ip).
  Eigen::MatrixXd dvec(rows, 3);
  Eigen::VectorXd cos_pd(rows), sin_td_row(rows), cos_td_row(rows);
  for (int id = 0; id < nd; ++id) {
    const double td = grid.ThetaDAt(id + 0.5);
    for (int ip = 0; ip < np; ++ip) {
      const double pd = grid.PhiDAt(ip + 0.5);
      const Eigen::Index r = static_cast<Eigen::Index>(id) * np + ip;
      dvec.row(r) << std::sin(td) * std::cos(pd), std::sin(td) * std::sin(pd), std::cos(td);
      cos_pd[r] = std::cos(pd);
      sin_td_row[r] = std::sin(td);
      cos_td_row[r] = std::cos(td);
    }
  }
  const Eigen::MatrixXd p = (dvec * net.k1.bottomRows(3)).rowwise() + net.b1;
  // The hidden layers four cells at a time with AVX2 + FMA where the CPU has them
  // (io/nbrdf_forward.h: the same values to ~1e-15 relative, not the same bits), else Eigen.
  const bool vectorized = NbrdfForwardVectorized();

  struct Counts {
    std::size_t below = 0, clamped_values = 0, clamped_cells = 0;
    bool non_finite = false;
    std::size_t non_finite_cell = 0;
  };
  auto slice = [&](int ih, Counts& cnt, std::vector<Eigen::Index>& above) {
    const double th = grid.ThetaHAt(ih + 0.5);
    const double sh = std::sin(th), ch = std::cos(th);
    // Only the cells above the horizon go through the network (a quarter of the MERL grid is
    // below it). Directions at the cell centre with phi_h = 0 (geometry.h FromHalfDiff):
    // wi.z = cos th cos td - sin th sin td cos pd, wo.z = cos th cos td + sin th sin td cos pd.
    above.clear();
    for (Eigen::Index r = 0; r < rows; ++r) {
      const double a = ch * cos_td_row[r], b = sh * sin_td_row[r] * cos_pd[r];
      if (a - b > 0 && a + b > 0) {
        above.push_back(r);
      } else {
        ++cnt.below;  // masked (valid stays 0, value 0)
      }
    }
    if (above.empty()) return;
    // x = (sin th, 0, cos th, d): the half-vector part adds one row vector to P. Fewer rows can
    // send some of them through Eigen's GEMM remainder path, which sums in another order: a
    // few values per table change in the last bits (<= 1.4e-13 relative, docs/fitting.md).
    const Eigen::RowVectorXd hpart = sh * net.k1.row(0) + ch * net.k1.row(2);
    // y(i, c): the network's log-space output of cell above[i].
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> y(above.size(), 3);
    if (vectorized) {
      NbrdfForwardArgs args;
      args.p = p.data();
      args.p_rows = static_cast<std::size_t>(p.rows());
      args.rows = above.data();
      args.n = above.size();
      args.hpart = hpart.data();
      args.k2 = net.k2.data();
      args.b2 = net.b2.data();
      args.k3 = net.k3.data();
      args.b3 = net.b3.data();
      args.h1 = static_cast<int>(net.k2.rows());
      args.h2 = static_cast<int>(net.k2.cols());
      NbrdfForwardAvx2(args, y.data());
    } else {
      const Eigen::MatrixXd h1 = (p(above, Eigen::all).rowwise() + hpart).cwiseMax(0.0);
      const Eigen::MatrixXd h2 = ((h1 * net.k2).rowwise() + net.b2).cwiseMax(0.0);
      y = (h2 * net.k3).rowwise() + net.b3;
    }
    const std::size_t base = grid.Index(ih, 0, 0);
    for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(above.size()); ++i) {
      const std::size_t idx = base + static_cast<std::size_t>(above[i]);
      bool clamped = false;
      for (int c = 0; c < 3; ++c) {
        double f = std::expm1(y(i, c));
        if (!std::isfinite(f) && !cnt.non_finite) {
          cnt.non_finite = true;
          cnt.non_finite_cell = idx;
        }
        if (f < 0) {
          f = 0;  // README: clamp negative outputs to 0 (counted)
          ++cnt.clamped_values;
          clamped = true;
        }
        t.rgb[3 * idx + c] = f;
      }
      cnt.clamped_cells += clamped;
      t.valid[idx] = 1;
    }
  };

  const int n_threads = std::clamp(threads, 1, grid.n_theta_h);
  std::vector<Counts> counts(n_threads);
  if (n_threads == 1) {
    std::vector<Eigen::Index> above;
    for (int ih = 0; ih < grid.n_theta_h; ++ih) slice(ih, counts[0], above);
  } else {
    std::vector<std::thread> pool;
    for (int k = 0; k < n_threads; ++k) {
      pool.emplace_back([&, k] {
        std::vector<Eigen::Index> above;
        for (int ih = k; ih < grid.n_theta_h; ih += n_threads) slice(ih, counts[k], above);
      });
    }
    for (auto& th : pool) th.join();
  }
  for (const Counts& c : counts) {
    if (c.non_finite) {
      throw InputError(net.source,
                       fmt::format("network output is not finite at cell {}", c.non_finite_cell));
    }
    out.below_horizon += c.below;
    out.clamped_values += c.clamped_values;
    out.clamped_cells += c.clamped_cells;
  }
  t.provenance.source = net.source;
  t.provenance.generator = "nbrdf";
  t.provenance.model = "nbrdf";
  nlohmann::ordered_json params;
  params["material"] = net.material;
  params["clamped_values"] = out.clamped_values;
  t.provenance.parameters_json = params.dump();
  return out;
}

}  // namespace brdfit
