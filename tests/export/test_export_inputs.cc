// What `brdfit export` reads (io/fit_params_json.h): the fit report or the JSON parameters,
// told apart by content, and every bad input refused with the file named.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "export/gltf.h"
#include "io/fit_params_json.h"
#include "io/fit_report.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;

void Write(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

// The message names the file and contains `what`.
void ExpectRefused(const fs::path& p, const std::string& what) {
  try {
    ReadFitsAnyFormat(p);
    FAIL() << p << " was accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(p.filename().string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  }
}

TEST(ExportInputs, ReportAndJsonReadAlike) {
  ScratchDir dir;
  const fs::path src = fs::path(BRDFIT_SOURCE_DIR) / "tests/export/data/fits.json";
  const auto from_json = ReadFitsAnyFormat(src);
  ASSERT_EQ(from_json.size(), 8u);
  const fs::path h5 = dir.path() / "fits.h5";
  WriteFitReport(from_json, h5);
  const auto from_h5 = ReadFitsAnyFormat(h5);
  ASSERT_EQ(from_h5.size(), from_json.size());
  for (std::size_t i = 0; i < from_h5.size(); ++i) {
    EXPECT_EQ(from_h5[i].result.model, from_json[i].result.model);
    EXPECT_EQ(from_h5[i].result.params, from_json[i].result.params);
    EXPECT_EQ(from_h5[i].result.at_bound, from_json[i].result.at_bound);
    EXPECT_EQ(from_h5[i].material, from_json[i].material);
  }
}

TEST(ExportInputs, BadInputsAreRefusedNamingTheFile) {
  ScratchDir dir;
  ExpectRefused(dir.path() / "missing.json", "no such file");
  Write(dir.path() / "garbage.json", "not json at all");
  ExpectRefused(dir.path() / "garbage.json", "not valid JSON: ");
  Write(dir.path() / "other.json", R"({"format": "something-else", "fits": []})");
  ExpectRefused(dir.path() / "other.json", "brdfit-fit-params");
  Write(dir.path() / "nofits.json", R"({"format": "brdfit-fit-params", "format_version": 1})");
  ExpectRefused(dir.path() / "nofits.json", "\"fits\"");
  for (const char* version : {"", R"(, "format_version": 9)", R"(, "format_version": "1")"}) {
    Write(dir.path() / "version.json",
          std::string(R"({"format": "brdfit-fit-params", "fits": [])") + version + "}");
    ExpectRefused(dir.path() / "version.json", "is not supported (this brdfit reads 1)");
  }
  Write(dir.path() / "bounds.json",
        R"({"format": "brdfit-fit-params", "format_version": 1, "fits": [{"model": "lambert+ggx-hc",
            "status": "converged", "params": {"lambert.kd_r": 0.1, "lambert.kd_g": 0.1,
            "lambert.kd_b": 0.1, "ggx-hc.ks_r": 0.1, "ggx-hc.ks_g": 0.1, "ggx-hc.ks_b": 0.1,
            "ggx-hc.alpha": 7}}]})");
  ExpectRefused(dir.path() / "bounds.json", "ggx-hc.alpha");
  Write(
      dir.path() / "names.json",
      R"({"format": "brdfit-fit-params", "format_version": 1, "fits": [{"model": "ue4", "status": "converged",
            "params": {"base_r": 0.1}}]})");
  ExpectRefused(dir.path() / "names.json", "params");
  Write(dir.path() / "model.json",
        R"({"format": "brdfit-fit-params", "format_version": 1, "fits": [{"model": "nonsense",
            "status": "converged", "params": {}}]})");
  ExpectRefused(dir.path() / "model.json", "nonsense");
  Write(
      dir.path() / "type.json",
      R"({"format": "brdfit-fit-params", "format_version": 1, "fits": [{"model": "ue4", "status": "converged",
            "params": {"base_r": "red"}}]})");
  ExpectRefused(dir.path() / "type.json", "not a number");
}

// The .gltf names its .bin by a relative URI: a file name with '#', '?', '%' or a space is
// percent-encoded (RFC 3986), or a loader reads "a" and a fragment "b%41 c?.bin".
TEST(ExportGltf, TheBufferUriIsPercentEncoded) {
  exports::Provenance p;
  p.material = "m";
  const exports::GltfFiles f = exports::BuildGltf(exports::GltfPbr{}, p, "a#b%41 c?é.bin");
  const auto j = nlohmann::json::parse(f.json);
  EXPECT_EQ(j["buffers"][0]["uri"], "a%23b%2541%20c%3F%C3%A9.bin");
  EXPECT_EQ(
      nlohmann::json::parse(
          exports::BuildGltf(exports::GltfPbr{}, p, "gold-paint_2.bin").json)["buffers"][0]["uri"],
      "gold-paint_2.bin");
}

}  // namespace
}  // namespace brdfit
