// The io commands through the executable: one-line errors with exit code 2 for each bad input,
// synth -> info, determinism of the bytes, parameter-name errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>

#include "io/merl.h"
#include "io/table_io.h"
#include "io/tensor_file.h"
#include "io_test_util.h"
#include "tests/io/rgl_bsdf_test_files.h"

namespace brdfit {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using testing_io::CliResult;
using testing_io::CountLines;
using testing_io::RunCli;
using testing_io::ScratchDir;

// A valid MERL file (all zeros) as bytes, to be damaged by each test.
std::vector<char> MerlBytes() {
  std::vector<char> b(kMerlFileBytes, 0);
  const std::int32_t dims[3] = {90, 90, 180};
  std::memcpy(b.data(), dims, sizeof(dims));
  return b;
}

// `brdfit info FILE` fails with exit code 2 and exactly one line naming the file and problem.
void ExpectOneLineError(const ScratchDir& dir, const std::filesystem::path& file,
                        const std::string& problem) {
  const CliResult r = RunCli({"info", file.string()}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(CountLines(r.err), 1) << r.err;
  EXPECT_THAT(r.err, StartsWith("brdfit: error: " + file.string() + ": "));
  EXPECT_THAT(r.err, HasSubstr(problem));
  EXPECT_EQ(r.out, "");
}

TEST(CliInfoErrors, WrongHeaderDimension) {
  ScratchDir dir;
  auto b = MerlBytes();
  const std::int32_t bad = 91;
  std::memcpy(b.data() + 4, &bad, 4);
  testing_io::WriteBytes(dir / "dim.binary", b.data(), b.size());
  ExpectOneLineError(dir, dir / "dim.binary",
                     "header dimension 2 (theta_d bins) is 91, expected 90");
}

TEST(CliInfoErrors, WrongSize) {
  ScratchDir dir;
  auto b = MerlBytes();
  b.push_back(0);
  testing_io::WriteBytes(dir / "size.binary", b.data(), b.size());
  ExpectOneLineError(dir, dir / "size.binary", "file is 34992013 bytes, expected 34992012");
}

// A text file given as a table (a path mistyped, /etc/passwd) is not read as a MERL header.
TEST(CliInfoErrors, TextFileIsNotATable) {
  ScratchDir dir;
  const std::string text =
      "root:x:0:0:root:/root:/bin/bash\nbin:x:2:2:bin:/bin:/usr/sbin/nologin\n";
  testing_io::WriteBytes(dir / "passwd", text.data(), text.size());
  ExpectOneLineError(dir, dir / "passwd",
                     "not a table brdfit reads: no HDF5 or RGL .bsdf signature, and not a MERL "
                     ".binary (its header would give a 1953460082 x 809138234 x 1916416058 grid");
}

TEST(CliInfoErrors, TruncatedBody) {
  ScratchDir dir;
  auto b = MerlBytes();
  b.resize(b.size() / 2);
  testing_io::WriteBytes(dir / "cut.binary", b.data(), b.size());
  ExpectOneLineError(dir, dir / "cut.binary", "truncated: file is 17496006 bytes");
}

TEST(CliInfoErrors, NaNValue) {
  ScratchDir dir;
  auto b = MerlBytes();
  const double nan = std::nan("");
  std::memcpy(b.data() + 12 + 8 * 100, &nan, 8);
  testing_io::WriteBytes(dir / "nan.binary", b.data(), b.size());
  ExpectOneLineError(dir, dir / "nan.binary", "NaN at cell 100 (theta_h 0, theta_d 0, phi_d 100)");
}

TEST(CliInfoErrors, Directory) {
  ScratchDir dir;
  std::filesystem::create_directory(dir / "folder.binary");
  ExpectOneLineError(dir, dir / "folder.binary", "is a directory");
}

TEST(CliInfoErrors, MissingPath) {
  ScratchDir dir;
  ExpectOneLineError(dir, dir / "absent.binary", "no such file");
}

TEST(CliInfoErrors, BrokenHdf5Table) {
  ScratchDir dir;
  const char sig[] = "\211HDF\r\n\032\nnot really";
  testing_io::WriteBytes(dir / "broken.h5", sig, sizeof(sig));
  const CliResult r = RunCli({"info", (dir / "broken.h5").string()}, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(CountLines(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr((dir / "broken.h5").string() + ": "));
}

nlohmann::json InfoJson(const ScratchDir& dir, const std::filesystem::path& file) {
  const CliResult r = RunCli({"info", "--json", file.string()}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

TEST(CliSynth, InfoReportsTheRequestedHolesAndParameters) {
  ScratchDir dir;
  const auto out = dir / "t.h5";
  const CliResult r = RunCli({"synth", "--model", "lambert+ggx", "--param", "ggx.alpha=0.2",
                              "--param", "kd_r=0.3", "--grid", "30,30,60", "--missing", "0.3",
                              "--noise", "0.05", "--seed", "7", "-o", out.string()},
                             dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("wrote " + out.string()));
  const nlohmann::json j = InfoJson(dir, out);
  EXPECT_EQ(j["format"], "h5");
  EXPECT_EQ(j["grid"]["n_theta_h"], 30);
  EXPECT_EQ(j["grid"]["theta_h_mapping"], "sqrt");
  const double above = j["cells"].get<double>() - j["below_horizon"].get<double>();
  EXPECT_NEAR(j["missing_fraction_above_horizon"].get<double>(), 0.3, 0.5 / above);
  EXPECT_EQ(j["provenance"]["missing_fraction"], 0.3);
  EXPECT_EQ(j["provenance"]["noise"], 0.05);
  EXPECT_EQ(j["provenance"]["seed"], 7);
  EXPECT_EQ(j["provenance"]["model"], "lambert+ggx");
  EXPECT_EQ(j["provenance"]["parameters"]["ggx.alpha"], 0.2);
  EXPECT_EQ(j["provenance"]["parameters"]["lambert.kd_r"], 0.3);
  EXPECT_EQ(j["directional_albedo"].size(), 4u);
  // The text form says the same.
  const CliResult text = RunCli({"info", out.string()}, dir.path());
  EXPECT_THAT(text.out, HasSubstr("holes above the horizon"));
  EXPECT_THAT(text.out, HasSubstr("(30.00 % of"));
  EXPECT_THAT(text.out, HasSubstr("\"ggx.alpha\":0.2"));
}

TEST(CliSynth, SameSeedSameBytesInBothFormats) {
  ScratchDir dir;
  for (const std::string name : {"a.h5", "b.h5", "a.binary", "b.binary"}) {
    std::vector<std::string> args = {"synth",
                                     "--model",
                                     "ggx",
                                     "--noise",
                                     "0.1",
                                     "--missing",
                                     "0.25",
                                     "--seed",
                                     "3",
                                     "-o",
                                     (dir / name).string()};
    if (name.ends_with(".h5")) {
      args.insert(args.end(), {"--grid", "20,20,40", "--mapping", "linear"});
    }
    ASSERT_EQ(RunCli(args, dir.path()).exit_code, 0) << name;
  }
  EXPECT_EQ(testing_io::ReadBytes(dir / "a.h5"), testing_io::ReadBytes(dir / "b.h5"));
  EXPECT_EQ(testing_io::ReadBytes(dir / "a.binary"), testing_io::ReadBytes(dir / "b.binary"));
  ASSERT_EQ(RunCli({"synth", "--model", "ggx", "--noise", "0.1", "--missing", "0.25", "--seed", "4",
                    "--grid", "20,20,40", "--mapping", "linear", "-o", (dir / "c.h5").string()},
                   dir.path())
                .exit_code,
            0);
  EXPECT_NE(testing_io::ReadBytes(dir / "a.h5"), testing_io::ReadBytes(dir / "c.h5"));
}

TEST(CliSynth, BadParametersAndOptionsAreUsageErrors) {
  ScratchDir dir;
  const std::string out = (dir / "x.h5").string();
  CliResult r =
      RunCli({"synth", "--model", "lambert+ggx", "--param", "beta=1", "-o", out}, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(CountLines(r.err), 1);
  EXPECT_THAT(r.err, HasSubstr("unknown parameter 'beta' for model lambert+ggx; valid: "));
  EXPECT_THAT(r.err, HasSubstr("ggx.alpha (alpha)"));
  r = RunCli({"synth", "--model", "no-such-model", "-o", out}, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("unknown model 'no-such-model'; known models: "));
  r = RunCli({"synth", "--model", "ggx", "--grid", "45,45,90", "-o", (dir / "x.binary").string()},
             dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("MERL files hold only the 90,90,180 grid"));
  r = RunCli({"synth", "--model", "ggx", "--grid", "45,45", "-o", out}, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  r = RunCli({"synth", "--model", "ggx", "--missing", "1.5", "-o", out}, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  r = RunCli({"synth", "--model", "ggx", "-o", (dir / "x.txt").string()}, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("cannot tell the format"));
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(CliSynth, NbrdfMaterialOnAnyGrid) {
  const auto zip = std::filesystem::path(BRDFIT_SHARED_DATA) / "merl_nbrdf.zip";
  if (!std::filesystem::exists(zip)) GTEST_SKIP() << zip.string() << " not found, skipping";
  ScratchDir dir;
  const auto out = dir / "n.h5";
  const CliResult r = RunCli({"synth", "--nbrdf", "pink-felt", "--nbrdf-zip", zip.string(),
                              "--grid", "16,16,32", "--missing", "0.1", "-o", out.string()},
                             dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = InfoJson(dir, out);
  EXPECT_EQ(j["provenance"]["generator"], "nbrdf");
  EXPECT_EQ(j["provenance"]["parameters"]["material"], "pink-felt");
  const CliResult list = RunCli({"synth", "--list-nbrdf", "--nbrdf-zip", zip.string()}, dir.path());
  EXPECT_EQ(CountLines(list.out), 100);
  const CliResult bad =
      RunCli({"synth", "--nbrdf", "pink-felted", "--nbrdf-zip", zip.string(), "-o", out.string()},
             dir.path());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("no material 'pink-felted'"));
}

// An RGL .bsdf through the commands: info names the format and what the file does not cover, a
// damaged one gets one line naming its field, and a fit recovers the GGX roughness it was
// written with (the file stores f_r = c D G1(wi) / (4 cos_i cos_o): Smith's G1 of the light
// only, so alpha comes back within a few per cent, not exactly).
TEST(CliRglBsdf, InfoAndFitReadTheFile) {
  ScratchDir dir;
  const double alpha = 0.3, c[3] = {0.9, 0.6, 0.3};
  const std::filesystem::path file = dir.path() / "ggx.bsdf";
  WriteTensorFile(test::GgxBsdf(test::BsdfSpec{}, alpha, c), file);
  const nlohmann::json info = InfoJson(dir, file);
  EXPECT_EQ(info["format"], "bsdf");
  EXPECT_GT(info["not_covered_by_file"].get<double>(), 0);
  EXPECT_EQ(info["provenance"]["generator"], "rgl-bsdf");

  const std::filesystem::path json = dir.path() / "fit.json";
  const CliResult r =
      RunCli({"fit", file.string(), "--model", "ggx", "--diffuse", "none", "--polish", "none", "-o",
              (dir.path() / "fit.h5").string(), "--json", json.string()},
             dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  const nlohmann::json& params = j["fits"][0]["params"];
  EXPECT_NEAR(params["alpha"].get<double>(), alpha, 0.03 * alpha) << r.out;
  // The colour comes through: ks's channels in the file's ratio 0.9 : 0.6 : 0.3.
  EXPECT_NEAR(params["ks_g"].get<double>() / params["ks_r"].get<double>(), c[1] / c[0], 0.01);
  EXPECT_NEAR(params["ks_b"].get<double>() / params["ks_r"].get<double>(), c[2] / c[0], 0.01);

  // convert: the .bsdf as a MERL file keeps its valid cells and its mask.
  const std::string merl = (dir.path() / "ggx.binary").string();
  const CliResult conv = RunCli({"convert", file.string(), "-o", merl}, dir.path());
  ASSERT_EQ(conv.exit_code, 0) << conv.err;
  EXPECT_EQ(InfoJson(dir, merl)["valid"], info["valid"]);
  EXPECT_EQ(RunCli({"convert", file.string(), "-o", (dir.path() / "x.bsdf").string()}, dir.path())
                .exit_code,
            2);

  std::vector<char> bytes = testing_io::ReadBytes(file);
  bytes.resize(bytes.size() - 10);
  const std::filesystem::path cut = dir.path() / "cut.bsdf";
  testing_io::WriteBytes(cut, bytes.data(), bytes.size());
  ExpectOneLineError(dir, cut, "field 'rgb'");
}

// The description of a written .bsdf (non-empty when it reads as one with spectra).
std::string tensor_check(const std::string& path) {
  const TensorFile f = ReadTensorFile(path);
  const TensorField* d = f.Find("description");
  return f.Find("spectra") && d ? std::string(d->bytes.begin(), d->bytes.end()) : "";
}

// `export --format bsdf` from a synthetic table, and a fit of the file it wrote recovers the
// table's parameters (measured: alpha 0.151 for 0.15, kd and ks within 1.5 %); the output may
// not be an input, nor a folder.
TEST(CliRglBsdf, ExportedTableFitsBackToItsParameters) {
  ScratchDir dir;
  const std::string table = (dir.path() / "t.binary").string();
  const std::string bsdf = (dir.path() / "t.bsdf").string();
  ASSERT_EQ(RunCli({"synth", "--model", "lambert+ggx", "--param", "lambert.kd_r=0.3", "--param",
                    "lambert.kd_g=0.2", "--param", "lambert.kd_b=0.1", "--param", "ggx.ks_r=0.6",
                    "--param", "ggx.ks_g=0.6", "--param", "ggx.ks_b=0.6", "--param",
                    "ggx.alpha=0.15", "-o", table},
                   dir.path())
                .exit_code,
            0);
  const CliResult e = RunCli({"export", table, "--format", "bsdf", "-o", bsdf}, dir.path());
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_THAT(e.out, HasSubstr("table " + table + " -> " + bsdf));
  const std::string json = (dir.path() / "fit.json").string();
  const CliResult f = RunCli({"fit", bsdf, "--model", "lambert+ggx", "--polish", "none", "-o",
                              (dir.path() / "fit.h5").string(), "--json", json},
                             dir.path());
  ASSERT_EQ(f.exit_code, 0) << f.err;
  std::ifstream in(json);
  const nlohmann::json p = nlohmann::json::parse(in)["fits"][0]["params"];
  EXPECT_NEAR(p["ggx.alpha"].get<double>(), 0.15, 0.15 * 0.03);
  EXPECT_NEAR(p["lambert.kd_r"].get<double>(), 0.3, 0.3 * 0.05);
  EXPECT_NEAR(p["lambert.kd_b"].get<double>(), 0.1, 0.1 * 0.05);
  EXPECT_NEAR(p["ggx.ks_g"].get<double>(), 0.6, 0.6 * 0.03);

  // A factorization of the table, written as a .bsdf, reads back near the table (the
  // factorization's own error included; measured median 0.7 %).
  const std::string factors = (dir.path() / "factors").string();
  ASSERT_EQ(RunCli({"factor", table, "-o", factors}, dir.path()).exit_code, 0);
  const std::string fbsdf = (dir.path() / "f.bsdf").string();
  const CliResult fe =
      RunCli({"export", factors + "/t.factor.json", "--format", "bsdf", "-o", fbsdf}, dir.path());
  ASSERT_EQ(fe.exit_code, 0) << fe.err;
  EXPECT_THAT(fe.out, HasSubstr("factorization t.factor.json -> "));
  {
    const Table a = LoadTable(table), b = LoadTable(fbsdf);
    std::vector<double> rel;
    for (std::size_t i = 0; i < a.grid.NumCells(); ++i) {
      if (a.valid[i] && b.valid[i]) rel.push_back(std::abs(b.Value(i)[1] / a.Value(i)[1] - 1));
    }
    std::sort(rel.begin(), rel.end());
    EXPECT_LT(rel[rel.size() / 2], 0.02);
  }

  // --bsdf-scene: a spectral file and the renderer's scene that reads it, beside it.
  for (const std::string& kind : {std::string("pbrt"), std::string("mitsuba")}) {
    const std::string out = (dir.path() / ("s-" + kind + ".bsdf")).string();
    const CliResult sc = RunCli({"export", table, "--format", "bsdf", "--bsdf-scene", kind,
                                 "--bsdf-warp", "8", "--bsdf-theta-i", "4", "-o", out},
                                dir.path());
    ASSERT_EQ(sc.exit_code, 0) << sc.err;
    EXPECT_THAT(sc.out, HasSubstr("spectral 360-830 nm"));
    const std::vector<char> text = testing_io::ReadBytes(
        std::filesystem::path(out).replace_extension(kind == "pbrt" ? ".pbrt" : ".xml"));
    const std::string scene(text.begin(), text.end());
    EXPECT_THAT(
        scene,
        HasSubstr(
            kind == "pbrt"
                ? "\"string type\" [ \"measured\" ]\n    \"string filename\" [ \"s-pbrt.bsdf\" ]"
                : "<bsdf type=\"measured\" id=\"brdfit-material\">\n    <string "
                  "name=\"filename\" value=\"s-mitsuba.bsdf\"/>"));
    EXPECT_NE(tensor_check(out), "");
  }
  // A hostile name in the Mitsuba scene is an escaped XML attribute, in its comment harmless.
  const std::string hostile = (dir.path() / "a&<b>--'.bsdf").string();
  const CliResult mx = RunCli({"export", table, "--format", "bsdf", "--bsdf-scene", "mitsuba",
                               "--bsdf-warp", "8", "--bsdf-theta-i", "4", "-o", hostile},
                              dir.path());
  ASSERT_EQ(mx.exit_code, 0) << mx.err;
  {
    const std::vector<char> x =
        testing_io::ReadBytes(std::filesystem::path(hostile).replace_extension(".xml"));
    const std::string xml(x.begin(), x.end());
    EXPECT_THAT(xml, HasSubstr("value=\"a&amp;&lt;b&gt;--&apos;.bsdf\""));
    const std::size_t open = xml.find("<!--") + 4, close = xml.find("-->");
    EXPECT_EQ(xml.substr(open, close - open).find("--"), std::string::npos);  // no early "--"
  }
  const CliResult quote = RunCli({"export", table, "--format", "bsdf", "--bsdf-scene", "pbrt", "-o",
                                  (dir.path() / "a\"b.bsdf").string()},
                                 dir.path());
  EXPECT_EQ(quote.exit_code, 2);
  EXPECT_THAT(quote.err, HasSubstr("a scene cannot name this file"));

  const CliResult onto = RunCli({"export", table, "--format", "bsdf", "-o", table}, dir.path());
  EXPECT_EQ(onto.exit_code, 2);
  EXPECT_THAT(onto.err, HasSubstr("also an input"));
  const CliResult folder = RunCli(
      {"export", table, "--format", "bsdf", "-o", (dir.path() / "out/").string()}, dir.path());
  EXPECT_EQ(folder.exit_code, 2);
  EXPECT_THAT(folder.err, HasSubstr("writes one file"));
}

}  // namespace
}  // namespace brdfit
