#include "pipeline/comparison_scene.h"

#include <filesystem>

#include "core/input_name.h"
#include "io/nbrdf.h"
#include "pipeline/factor_settings.h"

namespace brdfit::pipeline {

nlohmann::json ComparisonScene(const std::string& input, bool quick) {
  const std::string table = IsNbrdfInput(input) ? input : std::filesystem::absolute(input).string();
  const std::string name = MaterialName(input);
  nlohmann::json s = {
      {"camera", {{"position", {0, 0, 4}}, {"fov_deg", 30}}},
      {"lights",
       {{{"name", "key"}, {"type", "directional"}, {"direction", {1, 1, 1.5}}},
        {{"name", "fill"}, {"type", "point"}, {"position", {-3, 0.5, 3}}, {"intensity", 0.4}}}},
      {"materials",
       {{name, {{"type", "measured"}, {"table", table}}},
        {"fit", {{"type", "analytic"}, {"model", "lambert+ggx"}, {"fit_table", table}}}}},
      {"objects", {{{"name", "ball"}, {"material", name}}}},
      {"comparison", {{"measured", name}, {"fitted", "fit"}}}};
  // The factorization `brdfit factor TABLE` writes: the form chosen by rendered score, at its
  // default resolution (quick: 16^2).
  s["materials"]["factored"] = {{"type", "factored"},
                                {"table", table},
                                {"form", "auto"},
                                {"resolution", quick ? 16 : FactorSettings{}.resolution}};
  s["comparison"]["factored"] = "factored";
  return s;
}

bool IsTableInput(const std::string& arg) {
  if (IsNbrdfInput(arg)) return true;
  const std::string ext = std::filesystem::path(arg).extension().string();
  return ext == ".binary" || ext == ".h5" || ext == ".hdf5";
}

}  // namespace brdfit::pipeline
