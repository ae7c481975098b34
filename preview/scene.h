// A preview scene (docs/scenes.md): camera, objects, lights with Three.js r8x's semantics,
// materials, display settings. World space, right-handed, y up by default. Lengths in
// arbitrary scene units; angles in degrees in the file, radians here.
#pragma once

#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/enum_names.h"
#include "models/geometry.h"
#include "preview/explain.h"
#include "preview/mesh.h"
#include "preview/tonemap.h"

namespace brdfit::preview {

// The ranges a scene's numbers are checked against (preview/scene.cc, docs/scenes.md "Ranges"):
// positions within kMaxSceneCoordinate of the origin on each axis, lengths (radius, near) at
// least kMinSceneLength, colours, intensities and exposure at most kMaxSceneRadiometric. The
// renderer computes in 32-bit floats: inside these ranges no product of two of them overflows
// and the depth buffer still separates near and far.
inline constexpr double kMaxSceneCoordinate = 1e6;
inline constexpr double kMinSceneLength = 1e-6;
inline constexpr double kMaxSceneRadiometric = 1e6;

struct Camera {
  Vec3 position{0, 0, 4};
  Vec3 target{0, 0, 0};
  Vec3 up{0, 1, 0};
  double fov_y = 30.0 * kPi / 180.0;  // vertical field of view, radians
  double near = 0.1, far = 100.0;
};

enum class LightType { kDirectional, kPoint, kSpot };
inline constexpr auto kLightTypeNames =
    MakeEnumNames<LightType>("light type", {{LightType::kDirectional, "directional"},
                                            {LightType::kPoint, "point"},
                                            {LightType::kSpot, "spot"}});
constexpr const auto& EnumNamesOf(LightType) {
  return kLightTypeNames;
}

// Three.js r8x punctual lights. The shader receives colour * intensity; with punctual_pi the
// irradiance is pi (n.l) colour intensity (Three.js without PHYSICALLY_CORRECT_LIGHTS).
struct Light {
  std::string name;
  LightType type = LightType::kDirectional;
  Vec3 colour{1, 1, 1};
  double intensity = 1.0;
  Vec3 direction{0, 0, 1};  // directional: unit vector from the scene TOWARDS the light
  Vec3 position{0, 0, 5};   // point, spot
  Vec3 target{0, 0, 0};     // spot: the cone axis runs from position to target
  double distance = 0.0;    // range; 0 = unlimited (Three.js testLightInRange)
  double decay = 0.0;       // exponent of (1 - d / distance); 0 = none
  double angle = kPi / 6;   // spot: cone half-angle, radians (coneCos = cos(angle))
  double penumbra = 0.0;    // spot: penumbraCos = cos(angle (1 - penumbra)), Three.js
};

enum class MaterialKind { kAnalytic, kMeasured, kFactored };
inline constexpr auto kMaterialKindNames =
    MakeEnumNames<MaterialKind>("material kind", {{MaterialKind::kAnalytic, "analytic"},
                                                  {MaterialKind::kMeasured, "measured"},
                                                  {MaterialKind::kFactored, "factored"}});
constexpr const auto& EnumNamesOf(MaterialKind) {
  return kMaterialKindNames;
}

struct MaterialSpec {
  std::string name;
  MaterialKind kind = MaterialKind::kAnalytic;
  // kAnalytic: registry model name and the full parameter vector (defaults filled in), or a
  // fit report entry to take them from.
  std::string model;
  std::vector<double> params;
  std::filesystem::path fit_report;  // optional: parameters from a report (io/fit_report.h)
  std::string fit_material;          // entry of the report
  std::filesystem::path fit_table;   // optional: fit `model` to this table (cached on disk)
  // kMeasured: a table file. kFactored: the table to factor, or the factorization's files.
  std::filesystem::path table;
  std::filesystem::path factors;  // "<stem>.factor.json" sidecar of `brdfit factor`
  int factor_resolution = 32;     // when computed from `table`
  std::string factor_param = "mccool";
  int factor_rank = 1;          // when computed from `table`: products in the sum, 1..4
  bool factor_diffuse = false;  // ... and with a diffuse value
  // "form": "auto": the form `brdfit factor` chooses by rendered score from its candidates
  // (docs/factorization.md §14) instead of factor_param, factor_rank, factor_diffuse.
  bool factor_auto = false;
};

enum class ObjectShape { kSphere, kMesh };

struct Object {
  std::string name;
  ObjectShape shape = ObjectShape::kSphere;
  // Sphere: its centre and radius. Mesh: where its bounding sphere goes (mesh_normalize), or
  // a translation and a uniform scale of the file's coordinates.
  Vec3 centre{0, 0, 0};
  double radius = 1.0;
  std::string material;
  std::filesystem::path mesh_file;  // kMesh: an OBJ file
  bool mesh_normalize = true;
  std::shared_ptr<const Mesh> mesh;  // kMesh: in world space, set by LoadSceneMeshes

  // The sphere, or the placed mesh's bounding sphere (light culling).
  Vec3 BoundCentre() const { return mesh ? mesh->bound_centre : centre; }
  double BoundRadius() const { return mesh ? mesh->bound_radius : radius; }
};

// Panels of `brdfit render --compare`: the scene's objects drawn with each material in turn.
struct ComparisonSpec {
  std::string measured;             // a measured material
  std::vector<std::string> fitted;  // analytic materials (the first one is the error panel's)
  std::string factored;             // a factored material, or empty
};

struct Scene {
  std::filesystem::path source;  // the scene file, for messages and relative paths
  Camera camera;
  std::vector<Light> lights;
  std::vector<Object> objects;
  std::vector<MaterialSpec> materials;
  int width = 512, height = 512;
  Vec3 background{0, 0, 0};  // linear radiance
  bool punctual_pi = true;
  DisplaySettings display;
  bool has_comparison = false;
  ComparisonSpec comparison;

  const MaterialSpec* FindMaterial(const std::string& name) const;
};

// Names of the materials a render needs: those the objects reference, or, for a comparison,
// the comparison's panels.
std::set<std::string> UsedMaterials(const Scene& scene, bool comparison);

// Parses and validates a scene file; relative paths resolve against the file's folder.
// Throws InputError naming the file and the problem.
// Reads a scene file and loads the meshes its objects use (each file once; logged to `log`).
Scene LoadScene(const std::filesystem::path& path, ExplainLog* log = nullptr);

// Loads and places the meshes of a parsed scene (InputError naming the OBJ file).
void LoadSceneMeshes(Scene* scene, ExplainLog* log);
Scene ParseScene(const std::string& json_text, const std::filesystem::path& source);

}  // namespace brdfit::preview
