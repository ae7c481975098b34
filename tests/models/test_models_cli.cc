// `brdfit models [--json]`: every registered model with its parameters, as the registry has it.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "models/registry.h"

namespace brdfit {
namespace {

// Runs a command, returns its exit code and stdout.
int RunCommand(const std::string& cmd, std::string* out) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((cmd + " 2>/dev/null").c_str(), "r"), pclose);
  if (!pipe) return -1;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe.get())) > 0) out->append(buf.data(), n);
  const int status = pclose(pipe.release());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(ModelsCli, JsonListsEveryModelWithItsParameters) {
  std::string out;
  ASSERT_EQ(RunCommand(std::string(BRDFIT_EXE) + " models --json", &out), 0);
  const auto json = nlohmann::json::parse(out);
  ASSERT_EQ(json.size(), AllModels().size());
  for (std::size_t k = 0; k < json.size(); ++k) {
    const ModelInfo& m = AllModels()[k];
    const auto& j = json[k];
    EXPECT_EQ(j["name"], m.name);
    EXPECT_EQ(j["doc"], m.doc);
    EXPECT_EQ(j["energy_conserving"], m.energy_conserving);
    ASSERT_EQ(j["params"].size(), m.params.size()) << m.name;
    for (std::size_t i = 0; i < m.params.size(); ++i) {
      const auto& p = j["params"][i];
      EXPECT_EQ(p["name"], m.param_names[i]);
      EXPECT_EQ(p["unit"], std::string(m.params[i].unit));
      EXPECT_EQ(p["lower"].get<double>(), m.params[i].lower);
      EXPECT_EQ(p["upper"].get<double>(), m.params[i].upper);
      EXPECT_EQ(p["default"].get<double>(), m.params[i].init);
      EXPECT_EQ(p["log_scale"], m.params[i].log_scale);
      EXPECT_EQ(p["role"], m.params[i].role == ParamRole::kShape     ? "shape"
                           : m.params[i].role == ParamRole::kWeightR ? "weight_r"
                           : m.params[i].role == ParamRole::kWeightG ? "weight_g"
                                                                     : "weight_b");
    }
  }
}

TEST(ModelsCli, TextNamesEveryModelAndParameter) {
  std::string out;
  ASSERT_EQ(RunCommand(std::string(BRDFIT_EXE) + " models", &out), 0);
  for (const ModelInfo& m : AllModels()) {
    EXPECT_NE(out.find("\n" + m.name + "\n"), std::string::npos) << m.name;
    for (const auto& n : m.param_names) EXPECT_NE(out.find(n), std::string::npos) << n;
  }
}

TEST(ModelsCli, SelectsByNameAndRejectsUnknownNames) {
  std::string out;
  ASSERT_EQ(RunCommand(std::string(BRDFIT_EXE) + " models --json ggx cook-torrance", &out), 0);
  const auto json = nlohmann::json::parse(out);
  ASSERT_EQ(json.size(), 2u);
  EXPECT_EQ(json[1]["name"], "cook-torrance");
  std::string err;
  EXPECT_EQ(RunCommand(std::string(BRDFIT_EXE) + " models no-such-model", &err), 2);
}

}  // namespace
}  // namespace brdfit
