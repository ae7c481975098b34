// NBRDF networks (io/nbrdf.h) against an independent scalar evaluation of the formula in
// ../shared/data/README.md, with weights read here through a different path (libzip +
// H5LTopen_file_image + the HDF5 C API, float32 as stored). Skips when the archive is absent.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <zip.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.h"
#include "core/nbrdf_forward.h"
#include "io/nbrdf.h"

namespace brdfit {
namespace {

const std::filesystem::path kZip = std::filesystem::path(BRDFIT_SHARED_DATA) / "merl_nbrdf.zip";

#define SKIP_WITHOUT_ARCHIVE()                                                        \
  if (!std::filesystem::exists(kZip)) {                                               \
    GTEST_SKIP() << kZip.string() << " not found, skipping (see shared/data/README)"; \
  }

// Weights as stored: kernels [in][out] row-major float32, biases [out].
struct OracleNet {
  std::vector<float> k[3], b[3];
  int in[3] = {6, 0, 0}, out[3] = {0, 0, 3};
};

OracleNet LoadOracle(const std::string& material) {
  int err = 0;
  zip_t* z = zip_open(kZip.c_str(), ZIP_RDONLY, &err);
  EXPECT_NE(z, nullptr);
  const std::string member = "merl_nbrdf/" + material + ".h5";
  zip_stat_t st;
  zip_stat(z, member.c_str(), 0, &st);
  std::vector<char> buf(st.size);
  zip_file_t* f = zip_fopen(z, member.c_str(), 0);
  EXPECT_EQ(zip_fread(f, buf.data(), st.size), static_cast<zip_int64_t>(st.size));
  zip_fclose(f);
  zip_discard(z);
  const hid_t file = H5LTopen_file_image(buf.data(), buf.size(), 0);  // copies the image
  EXPECT_GE(file, 0);
  OracleNet n;
  for (int l = 0; l < 3; ++l) {
    const std::string base = "/dense_" + std::to_string(l + 1) + "/dense_" + std::to_string(l + 1);
    hsize_t dims[2] = {0, 0};
    H5LTget_dataset_info(file, (base + "/kernel:0").c_str(), dims, nullptr, nullptr);
    n.k[l].resize(dims[0] * dims[1]);
    n.b[l].resize(dims[1]);
    if (l > 0) n.in[l] = static_cast<int>(dims[0]);
    n.out[l] = static_cast<int>(dims[1]);
    H5LTread_dataset_float(file, (base + "/kernel:0").c_str(), n.k[l].data());
    H5LTread_dataset_float(file, (base + "/bias:0").c_str(), n.b[l].data());
  }
  H5Fclose(file);
  return n;
}

// README: x = (sin th, 0, cos th, sin td cos pd, sin td sin pd, cos td);
// h1 = relu(x K1 + b1); h2 = relu(h1 K2 + b2); y = h2 K3 + b3; f = exp(y) - 1.
std::array<double, 3> OracleEval(const OracleNet& n, double th, double td, double pd) {
  std::vector<double> x = {
      std::sin(th), 0.0, std::cos(th), std::sin(td) * std::cos(pd), std::sin(td) * std::sin(pd),
      std::cos(td)};
  for (int l = 0; l < 3; ++l) {
    std::vector<double> y(n.out[l]);
    for (int j = 0; j < n.out[l]; ++j) {
      double s = n.b[l][j];
      for (int i = 0; i < n.in[l]; ++i) s += x[i] * static_cast<double>(n.k[l][i * n.out[l] + j]);
      y[j] = (l < 2) ? std::max(s, 0.0) : s;
    }
    x = y;
  }
  return {std::exp(x[0]) - 1, std::exp(x[1]) - 1, std::exp(x[2]) - 1};
}

// Cell-centre angles written from MERL's layout (BRDFRead.cpp), not from Grid: theta_h index
// coordinate u = 90 sqrt(th / 90deg), centre at i + 0.5.
void MerlCentre(int ih, int id, int ip, double* th, double* td, double* pd) {
  const double u = (ih + 0.5) / 90.0;
  *th = u * u * kPi / 2;
  *td = (id + 0.5) / 90.0 * kPi / 2;
  *pd = (ip + 0.5) / 180.0 * kPi;
}

void ExpectClose(double got, double want, const std::string& where) {
  EXPECT_NEAR(got, want, 1e-12 + 1e-10 * std::fabs(want)) << where;
}

TEST(Nbrdf, ArchiveListsTheHundredMerlMaterials) {
  SKIP_WITHOUT_ARCHIVE();
  const auto names = ListNbrdfMaterials(kZip);
  EXPECT_EQ(names.size(), 100u);
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  for (const char* m : {"alum-bronze", "gold-metallic-paint", "pink-felt", "yellow-plastic"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), m), names.end()) << m;
  }
}

TEST(Nbrdf, ScalarEvaluationMatchesTheReadmeFormula) {
  SKIP_WITHOUT_ARCHIVE();
  const OracleNet oracle = LoadOracle("gold-metallic-paint");
  const NbrdfNetwork net = ReadNbrdf(kZip, "gold-metallic-paint");
  EXPECT_EQ(net.k1.rows(), 6);
  EXPECT_EQ(net.k3.cols(), 3);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const double th = u(rng) * kPi / 2, td = u(rng) * kPi / 2, pd = u(rng) * kPi;
    const auto want = OracleEval(oracle, th, td, pd);
    const auto got = EvalNbrdf(net, {th, td, pd});
    for (int c = 0; c < 3; ++c) ExpectClose(got[c], want[c], "point " + std::to_string(k));
  }
}

// The batched tabulation on the MERL grid at random cells, and the mask on every cell.
TEST(Nbrdf, MerlGridTabulationMatchesIndependentEvaluation) {
  SKIP_WITHOUT_ARCHIVE();
  for (const char* material : {"alum-bronze", "blue-metallic-paint", "pink-felt"}) {
    const OracleNet oracle = LoadOracle(material);
    const NbrdfTabulation tab = TabulateNbrdf(ReadNbrdf(kZip, material), Grid::Merl());
    const Table& t = tab.table;
    std::size_t below = 0;
    for (std::size_t i = 0; i < t.valid.size(); ++i) {
      const bool above = t.grid.CellAboveHorizon(i);
      below += !above;
      ASSERT_EQ(t.valid[i], above) << material << " cell " << i;
    }
    EXPECT_EQ(tab.below_horizon, below);
    std::mt19937_64 rng(11);
    int checked = 0;
    while (checked < 300) {
      const int ih = rng() % 90, id = rng() % 90, ip = rng() % 180;
      const std::size_t idx = ip + 180 * id + 16200 * ih;
      if (!t.valid[idx]) continue;
      double th, td, pd;
      MerlCentre(ih, id, ip, &th, &td, &pd);
      const auto want = OracleEval(oracle, th, td, pd);
      for (int c = 0; c < 3; ++c) {
        ExpectClose(t.Value(idx)[c], std::max(want[c], 0.0),
                    std::string(material) + " cell " + std::to_string(idx));
      }
      ++checked;
    }
    EXPECT_EQ(t.provenance.generator, "nbrdf");
    EXPECT_THAT(t.provenance.parameters_json, ::testing::HasSubstr(material));
  }
}

// Every cell of a small grid: values, clamping (README: negative outputs -> 0, counted) and the
// clamp count, against the oracle.
TEST(Nbrdf, SmallGridEveryCellAndClampCount) {
  SKIP_WITHOUT_ARCHIVE();
  const Grid g{24, 20, 36, ThetaHMapping::kLinear};
  for (const char* material : {"black-obsidian", "specular-black-phenolic", "white-marble"}) {
    const OracleNet oracle = LoadOracle(material);
    const NbrdfTabulation tab = TabulateNbrdf(ReadNbrdf(kZip, material), g);
    std::size_t clamped = 0;
    for (std::size_t i = 0; i < g.NumCells(); ++i) {
      ASSERT_EQ(tab.table.valid[i], g.CellAboveHorizon(i)) << i;
      if (!tab.table.valid[i]) continue;
      int ih, id, ip;
      g.Unindex(i, &ih, &id, &ip);
      const auto want = OracleEval(oracle, (ih + 0.5) / 24 * kPi / 2, (id + 0.5) / 20 * kPi / 2,
                                   (ip + 0.5) / 36 * kPi);
      for (int c = 0; c < 3; ++c) {
        clamped += want[c] < 0;
        ExpectClose(tab.table.Value(i)[c], std::max(want[c], 0.0),
                    std::string(material) + " " + std::to_string(i));
      }
    }
    // A value within rounding of zero could be classified differently by the two
    // evaluations; none is expected on these grids.
    EXPECT_EQ(tab.clamped_values, clamped) << material;
  }
}

TEST(Nbrdf, ThreadCountDoesNotChangeTheTable) {
  SKIP_WITHOUT_ARCHIVE();
  const NbrdfNetwork net = ReadNbrdf(kZip, "red-plastic");
  const Grid g{30, 30, 60, ThetaHMapping::kSqrt};
  EXPECT_EQ(TabulateNbrdf(net, g, 1).table, TabulateNbrdf(net, g, 3).table);
}

TEST(Nbrdf, UnknownMaterialAndMissingArchiveAreNamed) {
  SKIP_WITHOUT_ARCHIVE();
  EXPECT_THAT([] { ReadNbrdf(kZip, "unobtainium"); },
              ::testing::ThrowsMessage<InputError>(::testing::AllOf(
                  ::testing::HasSubstr("no material 'unobtainium' (the archive has 100: "),
                  ::testing::HasSubstr("alum-bronze"))));
  EXPECT_THAT([] { ListNbrdfMaterials("/nonexistent/merl_nbrdf.zip"); },
              ::testing::ThrowsMessage<InputError>("/nonexistent/merl_nbrdf.zip: no such file"));
}


// The vectorized hidden layers (AVX2 + FMA machines) against a plain double evaluation of the
// same network, cell by cell: a random network with odd layer sizes, rows that are consecutive,
// scattered and repeated, and every tail length of the 16-cell blocks. Skips without AVX2 + FMA.
TEST(Nbrdf, VectorizedHiddenLayersMatchPlainEvaluation) {
  if (!NbrdfForwardVectorized()) GTEST_SKIP() << "this CPU has no AVX2 + FMA";
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 0.5);
  const int h1 = 5, h2 = 7;
  const std::size_t p_rows = 101;
  std::vector<double> p(p_rows * h1), hpart(h1), k2(h1 * h2), b2(h2), k3(h2 * 3), b3(3);
  for (auto* v : {&p, &hpart, &k2, &b2, &k3, &b3}) {
    for (double& x : *v) x = g(rng);
  }
  std::vector<long> rows;
  for (long r = 0; r < 40; ++r) rows.push_back(r);         // consecutive
  for (long r = 40; r < 101; r += 3) rows.push_back(r);    // scattered
  rows.push_back(7);                                        // repeated
  for (std::size_t n = 0; n <= rows.size(); ++n) {
    NbrdfForwardArgs a;
    a.p = p.data();
    a.p_rows = p_rows;
    a.rows = rows.data();
    a.n = n;
    a.hpart = hpart.data();
    a.k2 = k2.data();
    a.b2 = b2.data();
    a.k3 = k3.data();
    a.b3 = b3.data();
    a.h1 = h1;
    a.h2 = h2;
    std::vector<double> y(3 * n + 1, -7.0);
    NbrdfForwardAvx2(a, y.data());
    EXPECT_EQ(y[3 * n], -7.0) << "wrote past the end, n = " << n;
    for (std::size_t i = 0; i < n; ++i) {
      double l1[h1], l2[h2];
      for (int j = 0; j < h1; ++j) l1[j] = std::max(p[j * p_rows + rows[i]] + hpart[j], 0.0);
      for (int k = 0; k < h2; ++k) {
        double acc = b2[k];
        for (int j = 0; j < h1; ++j) acc += k2[k * h1 + j] * l1[j];
        l2[k] = std::max(acc, 0.0);
      }
      for (int c = 0; c < 3; ++c) {
        double want = b3[c], scale = std::abs(b3[c]);
        for (int k = 0; k < h2; ++k) {
          want += k3[c * h2 + k] * l2[k];
          scale += std::abs(k3[c * h2 + k] * l2[k]);
        }
        ASSERT_NEAR(y[3 * i + c], want, 1e-14 * scale) << "n " << n << " cell " << i;
      }
    }
  }
}

}  // namespace
}  // namespace brdfit
