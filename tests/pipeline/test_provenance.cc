// Provenance of every output (core/provenance.h, docs/formats.md "Provenance"): brdfit's
// version, the command line as typed and the date, the input as given and its content hash,
// in the fit report (HDF5 root attributes, per-entry source_hash), the JSON parameters, the
// factorization sidecar and its EXR headers, and the HTML report; `--no-timings` leaves out
// what changes from run to run.
#include <gtest/gtest.h>
#include <H5Cpp.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "core/provenance.h"
#include "core/synth.h"
#include "io/exr_texture.h"
#include "io/fit_report.h"
#include "io/merl.h"
#include "io/table_io.h"
#include "models/registry.h"
#include "reliability/cli_process.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using testing_cli::ReadAll;

Table SmallTable(double alpha) {
  const ModelInfo& m = *FindModel("lambert+ggx");
  std::vector<double> p = m.DefaultParams();
  p.back() = alpha;
  SynthOptions o;
  o.noise = 0.02;
  o.seed = 4;
  return SynthesizeTable(
      Grid{24, 24, 48, ThetaHMapping::kSqrt},
      [&](const Geometry& g, double rgb[3]) { m.eval(p.data(), g, rgb); }, o);
}

std::string RootAttr(const fs::path& h5, const char* name) {
  H5::H5File f(h5.string(), H5F_ACC_RDONLY);
  if (!f.attrExists(name)) return "(absent)";
  H5::Attribute a = f.openAttribute(name);
  std::string v;
  a.read(a.getStrType(), v);
  return v;
}

class Provenance : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("brdfit_provenance_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "in");
    // Relative paths, as a user types them: the outputs must keep them relative.
    old_cwd_ = fs::current_path();
    fs::current_path(dir_);
  }
  void TearDown() override {
    fs::current_path(old_cwd_);
    fs::remove_all(dir_);
  }
  fs::path dir_, old_cwd_;
};

TEST(TableContentHash, FollowsTheDataNotTheContainer) {
  const Table t = SmallTable(0.1);
  const std::string h = TableContentHash(t);
  EXPECT_TRUE(std::regex_match(h, std::regex("t64:[0-9a-f]{16}"))) << h;
  EXPECT_EQ(TableContentHash(t), h);  // deterministic
  Table one_bit = t;
  std::uint64_t bits;
  std::memcpy(&bits, &one_bit.rgb[1234], 8);
  bits ^= 1;  // the last bit of one value
  std::memcpy(&one_bit.rgb[1234], &bits, 8);
  EXPECT_NE(TableContentHash(one_bit), h);
  Table masked = t;
  for (std::size_t i = 0; i < masked.valid.size(); ++i) {
    if (masked.valid[i]) {
      masked.valid[i] = 0;
      break;
    }
  }
  EXPECT_NE(TableContentHash(masked), h);
  Table other_grid = t;
  other_grid.grid.theta_h_mapping = ThetaHMapping::kLinear;
  EXPECT_NE(TableContentHash(other_grid), h);
  // Saved to HDF5 and read back: the same hash.
  const fs::path h5 = fs::temp_directory_path() / ("brdfit_hash_" + std::to_string(::getpid()) + ".h5");
  SaveTable(t, h5);
  EXPECT_EQ(TableContentHash(LoadTable(h5)), h);
  fs::remove(h5);
}

TEST_F(Provenance, FitReportJsonFactorAndHtmlSayWhatMadeThem) {
  const Table t = SmallTable(0.15);
  SaveTable(t, "in/t.h5");
  const std::string hash = TableContentHash(t);
  const std::regex iso(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)");

  // fit: report root attributes, per-entry hash, JSON.
  auto r = testing_cli::Run({"fit", "in/t.h5", "--model", "lambert+ggx", "-o", "fits.h5", "--json",
                "fits.json", "-q"},
               dir_ / "fit.log");
  ASSERT_EQ(r.code, 0) << r.log;
  EXPECT_EQ(RootAttr("fits.h5", "brdfit_version"), std::string(BrdfitVersion()));
  const std::string cmd = RootAttr("fits.h5", "command_line");
  EXPECT_NE(cmd.find("fit in/t.h5 --model lambert+ggx -o fits.h5"), std::string::npos) << cmd;
  EXPECT_EQ(cmd.find(dir_.string()), std::string::npos) << "no absolute path the user did not give";
  EXPECT_TRUE(std::regex_match(RootAttr("fits.h5", "created"), iso));
  EXPECT_EQ(ReadFitReport("fits.h5").at(0).source_hash, hash);
  const auto j = nlohmann::json::parse(ReadAll("fits.json"));
  EXPECT_EQ(j["provenance"]["brdfit_version"], std::string(BrdfitVersion()));
  EXPECT_EQ(j["provenance"]["command_line"], cmd);
  EXPECT_EQ(j["fits"][0]["source"], "in/t.h5");
  EXPECT_EQ(j["fits"][0]["source_hash"], hash);

  // --no-timings: the version and the hash stay, the command line and the date go, and two
  // runs with different outputs are byte-identical.
  r = testing_cli::Run({"fit", "in/t.h5", "--model", "lambert+ggx", "-o", "a.h5", "--json", "a.json", "-q",
           "--no-timings"},
          dir_ / "a.log");
  ASSERT_EQ(r.code, 0) << r.log;
  r = testing_cli::Run({"fit", "in/t.h5", "--model", "lambert+ggx", "--json", "b.json",
                        "--no-timings", "-q", "-o", "b.h5"},
                       dir_ / "b.log");
  ASSERT_EQ(r.code, 0) << r.log;
  EXPECT_EQ(RootAttr("a.h5", "command_line"), "(absent)");
  EXPECT_EQ(RootAttr("a.h5", "created"), "(absent)");
  EXPECT_EQ(RootAttr("a.h5", "brdfit_version"), std::string(BrdfitVersion()));
  const auto a = nlohmann::json::parse(ReadAll("a.json"));
  EXPECT_FALSE(a["provenance"].contains("command_line"));
  EXPECT_EQ(a["fits"][0]["source_hash"], hash);
  EXPECT_TRUE(ReadAll("a.h5") == ReadAll("b.h5")) << "another command line, the same report";
  EXPECT_EQ(ReadAll("a.json"), ReadAll("b.json"));

  // SOURCE_DATE_EPOCH fixes the date (reproducible outputs with their command line).
  setenv("SOURCE_DATE_EPOCH", "86400", 1);
  r = testing_cli::Run({"fit", "in/t.h5", "--model", "lambert+ggx", "-o", "e.h5", "-q"},
                       dir_ / "e.log");
  unsetenv("SOURCE_DATE_EPOCH");
  ASSERT_EQ(r.code, 0) << r.log;
  EXPECT_EQ(RootAttr("e.h5", "created"), "1970-01-02T00:00:00Z");

  // factor: sidecar and every EXR header.
  r = testing_cli::Run({"factor", "in/t.h5", "--param", "mccool", "--res", "16", "-o", "fac", "-q"},
          dir_ / "factor.log");
  ASSERT_EQ(r.code, 0) << r.log;
  const auto sidecar = nlohmann::json::parse(ReadAll("fac/t.factor.json"));
  EXPECT_EQ(sidecar["source"]["file"], "in/t.h5");
  EXPECT_EQ(sidecar["source"]["hash"], hash);
  EXPECT_EQ(sidecar["provenance"]["brdfit_version"], std::string(BrdfitVersion()));
  EXPECT_NE(sidecar["provenance"]["command_line"].get<std::string>().find("factor in/t.h5"),
            std::string::npos);
  ExrAttributes attrs;
  ReadRgbExr("fac/t.p.exr", &attrs);
  EXPECT_EQ(attrs["brdfit:brdfit_version"], std::string(BrdfitVersion()));
  EXPECT_EQ(attrs["brdfit:source"], "in/t.h5");
  EXPECT_EQ(attrs["brdfit:source_hash"], hash);
  EXPECT_TRUE(std::regex_match(attrs["brdfit:created"], iso));

  // report: the HTML footer.
  r = testing_cli::Run({"report", "fits.h5", "-o", "r.html", "-q"}, dir_ / "report.log");
  ASSERT_EQ(r.code, 0) << r.log;
  const std::string html = ReadAll("r.html");
  const auto at = html.find("id=\"provenance\"");
  ASSERT_NE(at, std::string::npos);
  const std::string footer = html.substr(at, 400);
  EXPECT_NE(footer.find("brdfit " + std::string(BrdfitVersion())), std::string::npos) << footer;
  EXPECT_NE(footer.find("report fits.h5 -o r.html"), std::string::npos) << footer;
}

}  // namespace
}  // namespace brdfit
