#include "preview/lights.h"

#include <algorithm>
#include <cmath>

namespace brdfit::preview {

double Smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

bool LightReachesSphere(const Light& light, const Vec3& centre, double radius, std::string* why) {
  if (light.type == LightType::kDirectional) return true;
  const Vec3 v = centre - light.position;
  const double dist = Length(v);
  if (light.distance > 0 && dist - radius >= light.distance) {
    *why = "out of range (distance " + std::to_string(light.distance) + ", nearest surface at " +
           std::to_string(dist - radius) + ")";
    return false;
  }
  if (light.type == LightType::kSpot && dist > radius) {
    const Vec3 axis = Normalize(light.target - light.position);
    const double to_centre = std::acos(std::clamp(Dot(axis, v) / dist, -1.0, 1.0));
    const double angular_radius = std::asin(radius / dist);
    if (to_centre - angular_radius >= light.angle) {
      *why = "outside the cone (axis to sphere " + std::to_string(to_centre * 180 / kPi) +
             " deg, cone " + std::to_string(light.angle * 180 / kPi) + " deg)";
      return false;
    }
  }
  return true;
}

Incident IncidentAt(const Light& light, const Vec3& position) {
  const Vec3 c = light.intensity * light.colour;
  Incident in;
  if (light.type == LightType::kDirectional) {
    in.direction = Normalize(light.direction);
    in.colour = c;
    in.visible = true;
    return in;
  }
  const Vec3 L = light.position - position;
  const double d = Length(L);
  in.direction = (1.0 / d) * L;
  const bool in_range = light.distance == 0 || d < light.distance;
  const double falloff =
      light.decay > 0 ? std::pow(std::clamp(1.0 - d / light.distance, 0.0, 1.0), light.decay) : 1.0;
  double spot = 1.0;
  if (light.type == LightType::kSpot) {
    const double cone_cos = std::cos(light.angle);
    const double penumbra_cos = std::cos(light.angle * (1 - light.penumbra));
    const double angle_cos = Dot(in.direction, Normalize(light.position - light.target));
    if (!(angle_cos > cone_cos)) return in;  // invisible
    spot = penumbra_cos > cone_cos ? Smoothstep(cone_cos, penumbra_cos, angle_cos) : 1.0;
  }
  if (!in_range) return in;
  in.colour = (falloff * spot) * c;
  in.visible = true;
  return in;
}

}  // namespace brdfit::preview
