#include "preview/scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/factor_form.h"
#include "core/suggest.h"
#include "io/input_file.h"
#include "io/nbrdf.h"
#include "io/unique_keys_json.h"
#include "models/registry.h"
#include "preview/material.h"

namespace brdfit::preview {

const MaterialSpec* Scene::FindMaterial(const std::string& name) const {
  for (const auto& m : materials) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

namespace {

using Json = nlohmann::json;
constexpr double kDeg = kPi / 180.0;

std::string Fmt(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

// Reads one JSON object strictly: every key must be consumed, so typos are errors.
class Reader {
 public:
  Reader(const Json& j, std::string where, const std::filesystem::path& file)
      : j_(j), where_(std::move(where)), file_(file) {
    if (!j.is_object()) Fail("must be a JSON object");
  }
  [[noreturn]] void Fail(const std::string& problem) const {
    throw InputError(file_, where_ + ": " + problem);
  }
  bool Has(const std::string& k) const { return j_.contains(k); }
  const Json& Raw(const std::string& k) {
    used_.insert(k);
    return j_.at(k);
  }
  double Number(const std::string& k, double def) {
    if (!Has(k)) return def;
    const Json& v = Raw(k);
    if (!v.is_number()) Fail("'" + k + "' must be a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) Fail("'" + k + "' must be finite");
    return d;
  }
  double Positive(const std::string& k, double def) {
    const double d = Number(k, def);
    if (!(d > 0)) Fail("'" + k + "' must be > 0");
    return d;
  }
  double NonNegative(const std::string& k, double def) {
    const double d = Number(k, def);
    if (d < 0) Fail("'" + k + "' must be >= 0");
    return d;
  }
  int Int(const std::string& k, int def) {
    if (!Has(k)) return def;
    const Json& v = Raw(k);
    if (!v.is_number_integer()) Fail("'" + k + "' must be an integer");
    return v.get<int>();
  }
  bool Bool(const std::string& k, bool def) {
    if (!Has(k)) return def;
    const Json& v = Raw(k);
    if (!v.is_boolean()) Fail("'" + k + "' must be true or false");
    return v.get<bool>();
  }
  std::string String(const std::string& k, const std::string& def) {
    if (!Has(k)) return def;
    const Json& v = Raw(k);
    if (!v.is_string()) Fail("'" + k + "' must be a string");
    return v.get<std::string>();
  }
  std::string RequiredString(const std::string& k) {
    if (!Has(k)) Fail("missing '" + k + "'");
    return String(k, "");
  }
  Vec3 Vector(const std::string& k, const Vec3& def) {
    if (!Has(k)) return def;
    const Json& v = Raw(k);
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() ||
        !v[2].is_number()) {
      Fail("'" + k + "' must be an array of 3 numbers");
    }
    const Vec3 r{v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z)) {
      Fail("'" + k + "' must be finite");
    }
    return r;
  }
  // A position in world units: each coordinate within kMaxSceneCoordinate.
  Vec3 Point(const std::string& k, const Vec3& def) {
    const Vec3 p = Vector(k, def);
    if (std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) > kMaxSceneCoordinate) {
      Fail("'" + k + "' must be within " + Fmt(kMaxSceneCoordinate) +
           " of the origin in x, y and z");
    }
    return p;
  }
  // A number in [lo, hi].
  double InRange(const std::string& k, double def, double lo, double hi) {
    const double d = Number(k, def);
    if (!(d >= lo)) Fail("'" + k + "' must be >= " + Fmt(lo));
    if (d > hi) Fail("'" + k + "' must be <= " + Fmt(hi));
    return d;
  }
  // A unit vector along a finite non-zero one. Scaled by its largest component first: the
  // length of (1e154, 1e154, 1e154) overflows, and normalizing by it gave a zero direction.
  Vec3 Direction(const std::string& k, const Vec3& def) {
    const Vec3 d = Vector(k, def);
    const double m = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    if (!(m > 0)) Fail("'" + k + "' must be a non-zero vector");
    return Normalize(Vec3{d.x / m, d.y / m, d.z / m});
  }
  Vec3 Colour(const std::string& k, const Vec3& def = {1, 1, 1}) {
    const Vec3 c = Vector(k, def);
    if (c.x < 0 || c.y < 0 || c.z < 0) Fail("'" + k + "' must be >= 0");
    if (std::max({c.x, c.y, c.z}) > kMaxSceneRadiometric) {
      Fail("'" + k + "' must be <= " + Fmt(kMaxSceneRadiometric));
    }
    return c;
  }
  std::filesystem::path Path(const std::string& k) {
    const std::string text = String(k, "");
    // nbrdf:NAME names a network of the NBRDF archive (pipeline/inputs.h), not a file.
    if (text.empty() || IsNbrdfInput(text)) return text;
    const std::filesystem::path p = text;
    return p.is_absolute() ? p : file_.parent_path() / p;
  }
  // Every key must have been read.
  void Done() const {
    for (auto it = j_.begin(); it != j_.end(); ++it) {
      if (!used_.count(it.key())) Fail("unknown key '" + it.key() + "'");
    }
  }
  const std::string& where() const { return where_; }

 private:
  const Json& j_;
  std::string where_;
  std::filesystem::path file_;
  std::set<std::string> used_;
};

Camera ParseCamera(Reader r) {
  Camera c;
  c.position = r.Point("position", c.position);
  c.target = r.Point("target", c.target);
  c.up = r.Direction("up", c.up);
  c.fov_y = r.Positive("fov_deg", 30.0) * kDeg;
  c.near = r.InRange("near", c.near, kMinSceneLength, kMaxSceneCoordinate);
  c.far = r.InRange("far", c.far, kMinSceneLength, 4 * kMaxSceneCoordinate);
  r.Done();
  if (c.fov_y >= kPi) r.Fail("'fov_deg' must be < 180");
  if (c.far <= c.near) r.Fail("'far' must exceed 'near'");
  if (!(Length(c.target - c.position) > 0)) r.Fail("'target' equals 'position'");
  if (Length(Cross(c.target - c.position, c.up)) < 1e-9 * Length(c.target - c.position)) {
    r.Fail("'up' is parallel to the viewing direction");
  }
  return c;
}

Light ParseLight(Reader r, int index) {
  Light l;
  l.name = r.String("name", "light" + std::to_string(index));
  const std::string type = r.RequiredString("type");
  const std::optional<LightType> kind = kLightTypeNames.Find(type);
  if (!kind) r.Fail(kLightTypeNames.Unknown(type));
  l.type = *kind;
  l.colour = r.Colour("color");
  l.intensity = r.InRange("intensity", 1.0, 0.0, kMaxSceneRadiometric);
  if (l.type == LightType::kDirectional) {
    if (!r.Has("direction")) r.Fail("a directional light needs 'direction' (towards the light)");
    l.direction = r.Direction("direction", l.direction);
  } else {
    if (!r.Has("position")) r.Fail("a " + type + " light needs 'position'");
    l.position = r.Point("position", l.position);
    l.distance = r.InRange("distance", 0.0, 0.0, 4 * kMaxSceneCoordinate);
    l.decay = r.InRange("decay", 0.0, 0.0, 1000.0);
    if (l.decay > 0 && l.distance == 0) {
      r.Fail("'decay' > 0 needs 'distance' > 0 (the falloff is (1 - d / distance)^decay, as "
             "Three.js point lights)");
    }
    if (l.type == LightType::kSpot) {
      l.target = r.Point("target", l.target);
      if (!(Length(l.target - l.position) > 0)) r.Fail("'target' equals 'position'");
      l.angle = r.Positive("angle_deg", 30.0) * kDeg;
      if (l.angle > kPi / 2) r.Fail("'angle_deg' must be <= 90 (Three.js)");
      l.penumbra = r.NonNegative("penumbra", 0.0);
      if (l.penumbra > 1) r.Fail("'penumbra' must be in [0, 1]");
    }
  }
  r.Done();
  return l;
}

// Analytic parameters: defaults from the model's table, overridden by name.
std::vector<double> ParseParams(Reader& r, const ModelInfo& model) {
  std::vector<double> p = model.DefaultParams();
  if (!r.Has("params")) return p;
  const Json& j = r.Raw("params");
  if (j.is_array()) {
    if (j.size() != p.size()) {
      r.Fail("'params' has " + std::to_string(j.size()) + " values, model '" + model.name +
             "' has " + std::to_string(p.size()));
    }
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!j[i].is_number()) r.Fail("'params' must hold numbers");
      p[i] = j[i].get<double>();
    }
  } else if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      std::size_t i = 0;
      while (i < p.size() && model.param_names[i] != it.key()) ++i;
      if (i == p.size()) {
        std::string names;
        for (const auto& n : model.param_names) names += (names.empty() ? "" : ", ") + n;
        r.Fail("model '" + model.name + "' has no parameter '" + it.key() + "' (" + names + ")");
      }
      if (!it->is_number()) r.Fail("parameter '" + it.key() + "' must be a number");
      p[i] = it->get<double>();
    }
  } else {
    r.Fail("'params' must be an object {name: value} or an array");
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    const ParamSpec& s = model.params[i];
    if (!(p[i] >= s.lower && p[i] <= s.upper)) {
      r.Fail("parameter '" + model.param_names[i] + "' = " + std::to_string(p[i]) +
             " is outside [" + std::to_string(s.lower) + ", " + std::to_string(s.upper) + "]");
    }
  }
  return p;
}

MaterialSpec ParseMaterial(Reader r, const std::string& name) {
  MaterialSpec m;
  m.name = name;
  const std::string type = r.RequiredString("type");
  if (type == "analytic") {
    m.kind = MaterialKind::kAnalytic;
    m.model = r.RequiredString("model");
    const ModelInfo* model = FindModel(m.model);
    if (!model) {
      r.Fail("unknown model '" + m.model + "'" + SuggestionAfter(m.model, AllModelNames()) +
             " (known: " + ModelNames() + ")");
    }
    m.fit_report = r.Path("fit_report");
    m.fit_material = r.String("fit_material", "");
    m.fit_table = r.Path("fit_table");
    if ((!m.fit_report.empty()) + (!m.fit_table.empty()) + r.Has("params") > 1) {
      r.Fail("give one of 'params', 'fit_report', 'fit_table'");
    }
    m.params = ParseParams(r, *model);
  } else if (type == "metallic-roughness") {
    // The metallic/roughness material of mebiusbox 2018's sample (albedo, metallic, perceptual
    // roughness r) as lambert+ggx at the edge where perceptual roughness enters
    // (docs/conventions.md): alpha = r^2, kd = albedo (1 - m), ks = mix(0.04, albedo, m)
    // (Fresnel at normal incidence folded into ks; that sample uses Schlick's F(v.h), see
    // docs/scenes.md).
    m.kind = MaterialKind::kAnalytic;
    m.model = "lambert+ggx";
    const Vec3 albedo = r.Colour("albedo");
    const double metallic = r.NonNegative("metallic", 0.0);
    const double roughness = r.Positive("roughness", 0.5);
    if (metallic > 1) r.Fail("'metallic' must be in [0, 1]");
    if (roughness > 1) r.Fail("'roughness' must be in (0, 1]");
    const double a[3] = {albedo.x, albedo.y, albedo.z};
    m.params.clear();
    for (double c : a) m.params.push_back(c * (1 - metallic));
    for (double c : a) m.params.push_back(0.04 * (1 - metallic) + c * metallic);
    m.params.push_back(std::max(roughness * roughness, 1e-4));
  } else if (type == "measured") {
    m.kind = MaterialKind::kMeasured;
    m.table = r.Path("table");
    if (m.table.empty()) r.Fail("a measured material needs 'table'");
  } else if (type == "factored") {
    m.kind = MaterialKind::kFactored;
    m.table = r.Path("table");
    m.factors = r.Path("factors");
    m.factor_resolution = r.Int("resolution", m.factor_resolution);
    m.factor_param = r.String("parameterization", m.factor_param);
    m.factor_rank = r.Int("rank", m.factor_rank);
    m.factor_diffuse = r.Bool("diffuse", m.factor_diffuse);
    const std::string form = r.String("form", "");
    if (!form.empty() && form != "auto") r.Fail("'form' must be \"auto\" (or left out)");
    m.factor_auto = form == "auto";
    if (m.factor_auto && !m.factors.empty()) {
      r.Fail("'form' chooses how a factorization of 'table' is computed; 'factors' is already one");
    }
    if (m.factor_auto && (r.Has("parameterization") || r.Has("rank") || r.Has("diffuse"))) {
      r.Fail("'form': \"auto\" chooses the parameterization, rank and diffuse value: leave "
             "them out");
    }
    if (m.table.empty() == m.factors.empty()) {
      r.Fail("a factored material needs either 'factors' (a .factor.json) or 'table' (to factor)");
    }
    if (m.factor_resolution < 4 || m.factor_resolution > kMaxFactorResolution) {
      r.Fail("'resolution' must be in [4, " + std::to_string(kMaxFactorResolution) + "]");
    }
    if ((m.factor_auto || m.factor_param == "halfdiff") &&
        m.factor_resolution > kMaxHalfDiffResolution) {
      r.Fail("'resolution' must be at most " + std::to_string(kMaxHalfDiffResolution) +
             (m.factor_auto ? " with \"form\": \"auto\" (it tries halfdiff" : " for halfdiff (") +
             ", whose q texture is solved texel by texel)");
    }
    if (m.factor_rank < 1 || m.factor_rank > kMaxFactorTextureTerms) {
      r.Fail("'rank' must be in [1, " + std::to_string(kMaxFactorTextureTerms) + "]");
    }
  } else {
    r.Fail("unknown material type '" + type +
           "' (expected analytic, metallic-roughness, measured, factored)");
  }
  r.Done();
  return m;
}

Object ParseObject(Reader r, int index) {
  Object o;
  o.name = r.String("name", "object" + std::to_string(index));
  const std::string shape = r.String("shape", "sphere");
  if (shape == "mesh") {
    o.shape = ObjectShape::kMesh;
    o.mesh_file = r.Path("file");
    if (o.mesh_file.empty()) r.Fail("a mesh object needs 'file' (a Wavefront .obj)");
    o.mesh_normalize = r.Bool("normalize", true);
  } else if (shape != "sphere") {
    r.Fail("unknown shape '" + shape + "' (expected sphere or mesh)");
  }
  o.centre = r.Point("centre", o.centre);
  o.radius = r.InRange("radius", 1.0, kMinSceneLength, kMaxSceneCoordinate);
  o.material = r.RequiredString("material");
  r.Done();
  return o;
}

}  // namespace

Scene ParseScene(const std::string& text, const std::filesystem::path& source) {
  Json j;
  try {
    j = ParseJsonUniqueKeys(text, source);  // a key twice is refused, naming it
  } catch (const Json::exception& e) {
    // Not only parse_error: a number too large for a double is out_of_range (406)
    // (fuzz/regressions/scene/number-overflow-41e308).
    throw InputError(source, std::string("invalid JSON: ") + e.what());
  }
  Scene s;
  s.source = source;
  Reader r(j, "scene", source);
  if (r.Has("camera")) s.camera = ParseCamera(Reader(r.Raw("camera"), "camera", source));
  if (r.Has("image")) {
    Reader ir(r.Raw("image"), "image", source);
    s.width = ir.Int("width", s.width);
    s.height = ir.Int("height", s.height);
    if (s.width < 1 || s.height < 1 || s.width > 8192 || s.height > 8192) {
      ir.Fail("width and height must be in [1, 8192]");
    }
    s.background = ir.Colour("background", s.background);
    ir.Done();
  }
  if (r.Has("display")) {
    Reader dr(r.Raw("display"), "display", source);
    try {
      s.display.tone_map = FromString<ToneMap>(dr.String("tone_map", "linear"));
      s.display.encoding = FromString<Encoding>(dr.String("encoding", "srgb"));
    } catch (const InputError& e) {
      dr.Fail(e.what());
    }
    s.display.exposure =
        dr.InRange("exposure", 1.0, 1 / kMaxSceneRadiometric, kMaxSceneRadiometric);
    s.display.white_point =
        dr.InRange("white_point", 1.0, 1 / kMaxSceneRadiometric, kMaxSceneRadiometric);
    dr.Done();
  }
  s.punctual_pi = r.Bool("punctual_pi", true);
  if (r.Has("lights")) {
    const Json& lights = r.Raw("lights");
    if (!lights.is_array()) r.Fail("'lights' must be an array");
    for (std::size_t i = 0; i < lights.size(); ++i) {
      s.lights.push_back(
          ParseLight(Reader(lights[i], "lights[" + std::to_string(i) + "]", source), int(i)));
    }
  }
  if (!r.Has("materials")) r.Fail("missing 'materials'");
  const Json& mats = r.Raw("materials");
  if (!mats.is_object()) r.Fail("'materials' must be an object {name: material}");
  for (auto it = mats.begin(); it != mats.end(); ++it) {
    s.materials.push_back(ParseMaterial(Reader(*it, "materials." + it.key(), source), it.key()));
  }
  if (!r.Has("objects")) r.Fail("missing 'objects'");
  const Json& objs = r.Raw("objects");
  if (!objs.is_array() || objs.empty()) r.Fail("'objects' must be a non-empty array");
  for (std::size_t i = 0; i < objs.size(); ++i) {
    Object o = ParseObject(Reader(objs[i], "objects[" + std::to_string(i) + "]", source), int(i));
    if (!s.FindMaterial(o.material)) {
      r.Fail("object '" + o.name + "' references unknown material '" + o.material + "'");
    }
    s.objects.push_back(std::move(o));
  }
  // A camera that sees no object renders the background alone: refused rather than drawn.
  const bool any_in_range = std::any_of(s.objects.begin(), s.objects.end(), [&](const Object& o) {
    const bool bounded = o.shape == ObjectShape::kSphere || o.mesh_normalize;  // by its radius
    return !bounded || Length(o.centre - s.camera.position) - o.radius < s.camera.far;
  });
  if (!any_in_range) {
    r.Fail("every object lies beyond the camera's 'far' (" + Fmt(s.camera.far) +
           "): nothing would be drawn");
  }
  if (r.Has("comparison")) {
    Reader cr(r.Raw("comparison"), "comparison", source);
    s.has_comparison = true;
    s.comparison.measured = cr.RequiredString("measured");
    if (cr.Has("fitted")) {
      const Json& f = cr.Raw("fitted");
      if (f.is_string()) {
        s.comparison.fitted.push_back(f.get<std::string>());
      } else if (f.is_array()) {
        for (const auto& e : f) {
          if (!e.is_string()) cr.Fail("'fitted' must hold material names");
          s.comparison.fitted.push_back(e.get<std::string>());
        }
      } else {
        cr.Fail("'fitted' must be a material name or an array of names");
      }
    }
    s.comparison.factored = cr.String("factored", "");
    cr.Done();
    auto check = [&](const std::string& name, MaterialKind kind) {
      const MaterialSpec* m = s.FindMaterial(name);
      if (!m) cr.Fail("unknown material '" + name + "'");
      if (m->kind != kind) {
        cr.Fail("material '" + name + "' is " + ToString(m->kind) + ", expected " + ToString(kind));
      }
    };
    check(s.comparison.measured, MaterialKind::kMeasured);
    for (const auto& f : s.comparison.fitted) check(f, MaterialKind::kAnalytic);
    if (!s.comparison.factored.empty()) check(s.comparison.factored, MaterialKind::kFactored);
  }
  r.Done();
  return s;
}

std::set<std::string> UsedMaterials(const Scene& scene, bool comparison) {
  std::set<std::string> used;
  if (comparison) {
    used.insert(scene.comparison.measured);
    used.insert(scene.comparison.fitted.begin(), scene.comparison.fitted.end());
    if (!scene.comparison.factored.empty()) used.insert(scene.comparison.factored);
  } else {
    for (const Object& o : scene.objects) used.insert(o.material);
  }
  return used;
}

void LoadSceneMeshes(Scene* scene, ExplainLog* log) {
  std::map<std::filesystem::path, std::shared_ptr<const Mesh>> files;
  for (Object& o : scene->objects) {
    if (o.shape != ObjectShape::kMesh) continue;
    auto it = files.find(o.mesh_file);
    if (it == files.end()) {
      auto mesh = std::make_shared<const Mesh>(LoadObj(o.mesh_file));
      if (log) {
        std::string what = "mesh " + o.mesh_file.string() + " (" +
                           std::to_string(mesh->NumTriangles()) + " triangles, " +
                           std::to_string(mesh->positions.size()) + " vertices";
        if (mesh->computed_normals) what += ", normals computed";
        if (mesh->dropped_triangles) {
          what += ", " + std::to_string(mesh->dropped_triangles) + " zero-area triangles left out";
        }
        log->Add("load", what + ")");
      }
      it = files.emplace(o.mesh_file, std::move(mesh)).first;
    } else if (log) {
      log->Add("reuse", "mesh " + o.mesh_file.string() + " for object '" + o.name + "'");
    }
    try {
      o.mesh = std::make_shared<const Mesh>(
          PlaceMesh(*it->second, o.centre, o.radius, o.mesh_normalize));
    } catch (const InputError& e) {
      throw InputError(scene->source, "object '" + o.name + "': " + e.what());
    }
  }
}

Scene LoadScene(const std::filesystem::path& path, ExplainLog* log) {
  CheckInputFile(path);  // a folder is "is a directory", not "invalid JSON ... end of input"
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open scene file");
  std::stringstream ss;
  ss << in.rdbuf();
  Scene scene = ParseScene(ss.str(), path);
  LoadSceneMeshes(&scene, log);
  return scene;
}

}  // namespace brdfit::preview
