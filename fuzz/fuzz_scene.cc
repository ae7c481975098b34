// Fuzz harness: preview scene files (preview/scene.h, ParseScene; docs/scenes.md). The input is
// the JSON text. Referenced tables, factorizations and fit reports are not loaded here (their
// readers have their own harnesses).
// After a successful parse, every documented constraint holds: finite camera with
// 0 < fov < 180 degrees and 0 < near < far; image 1..8192; lights finite and non-negative,
// spot cones within 90 degrees; at least one object, radii positive, every referenced
// material defined, model parameters finite.
#include <cmath>
#include <string>

#include "fuzz/harness_util.h"
#include "core/error.h"
#include "preview/scene.h"

namespace brdfit::fuzz {

namespace {

bool Finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool NonNegative(const Vec3& v) { return Finite(v) && v.x >= 0 && v.y >= 0 && v.z >= 0; }

void CheckScene(const preview::Scene& s) {
  const preview::Camera& c = s.camera;
  CheckInvariant(Finite(c.position) && Finite(c.target) && Finite(c.up), "camera not finite");
  CheckInvariant(c.fov_y > 0 && c.fov_y < kPi, "fov out of (0, pi)");
  CheckInvariant(c.near > 0 && c.far > c.near && std::isfinite(c.far), "near/far");
  CheckInvariant(s.width >= 1 && s.width <= 8192 && s.height >= 1 && s.height <= 8192, "image");
  CheckInvariant(Finite(s.background), "background");
  for (const auto& l : s.lights) {
    CheckInvariant(NonNegative(l.colour) && std::isfinite(l.intensity) && l.intensity >= 0,
                   "light colour or intensity");
    CheckInvariant(Finite(l.direction) && Finite(l.position) && Finite(l.target), "light vectors");
    CheckInvariant(std::isfinite(l.distance) && l.distance >= 0 && std::isfinite(l.decay) &&
                       l.decay >= 0,
                   "light range");
    if (l.type == preview::LightType::kSpot) {
      CheckInvariant(l.angle > 0 && l.angle <= kPi / 2 && l.penumbra >= 0 && l.penumbra <= 1,
                     "spot cone");
    }
  }
  CheckInvariant(!s.objects.empty(), "no objects");
  for (const auto& o : s.objects) {
    CheckInvariant(Finite(o.centre) && std::isfinite(o.radius) && o.radius > 0, "object");
    CheckInvariant(s.FindMaterial(o.material) != nullptr, "object material undefined");
  }
  for (const auto& m : s.materials) {
    for (double p : m.params) CheckInvariant(std::isfinite(p), "non-finite model parameter");
  }
  for (const bool comparison : {false, true}) {
    if (comparison && !s.has_comparison) continue;
    for (const auto& name : preview::UsedMaterials(s, comparison)) {
      CheckInvariant(s.FindMaterial(name) != nullptr, "used material undefined");
    }
  }
}

}  // namespace

int FuzzScene(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  preview::Scene scene;
  try {
    scene = preview::ParseScene(text, ScratchDir() / "scene.json");
  } catch (const InputError&) {
    return 0;
  }
  CheckScene(scene);
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzScene)
