// Three.js r8x light semantics on the CPU: which lights can reach an object (culling before the
// shader is generated) and the incident light at a point (the CPU reference renderer).
#pragma once

#include <string>

#include "models/geometry.h"
#include "preview/scene.h"

namespace brdfit::preview {

// False if the light cannot reach any point of the sphere: a point or spot light whose range
// (distance > 0) ends before the sphere, or a spot whose cone misses it. *why says which.
bool LightReachesSphere(const Light& light, const Vec3& centre, double radius, std::string* why);

// Three.js getXDirectLightIrradiance in world space: direction towards the light and the
// light colour (colour * intensity * range/decay/cone factors) at a surface point.
struct Incident {
  Vec3 direction;
  Vec3 colour;
  bool visible = false;
};
Incident IncidentAt(const Light& light, const Vec3& position);

// Three.js smoothstep (GLSL definition): Hermite between edge0 and edge1.
double Smoothstep(double edge0, double edge1, double x);

}  // namespace brdfit::preview
