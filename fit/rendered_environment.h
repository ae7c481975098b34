// The environment of the rendered-image metric (docs/accuracy.md, "The environment"): the
// sphere of fit/rendered_error.h lit from every direction at once, by a sky and a sun, as a
// scene lights a material. Its image covers theta_d over its whole range (the sky's light arrives
// from in front, beside and behind every pixel), weighted by what a camera sees.
//
// World space is the metric's: the camera looks along -z from +z, y up. The sky (a gradient, a
// neutral overcast-to-clear ramp; no colour, so that the image's colour is the material's):
//   L_sky(w) = 0.25 + 0.75 w_y    for w_y >= 0 (zenith 1, horizon 0.25)
//            = 0.1                for w_y < 0   (the ground)
// and a sun, a directional light of the given irradiance at normal incidence: high and behind
// the sphere at the defaults, so that its image has a lit crescent the studio's front lights
// never show, next to the sky's soft body.
//
// Per pixel, L = sum_j f(w_j, wo) L_sky(w_j) cos_j / (K p(w_j)) + f(l_sun, wo) E_sun cos_sun:
// the sky by K directions drawn from a fixed mixture of three densities (Veach & Guibas 1995,
// "Optimally combining sampling techniques", the balance heuristic with K/3 samples from each:
// p = (p_cos + p_D(0.3) + p_D(0.03)) / 3): cosine-weighted directions (Malley's method) for the
// body, and directions reflected about GGX half vectors of roughness 0.3 and 0.03 around the
// view (Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
// Surfaces", Eqs. 33 and 35-36 and 38) for glossy and sharp highlights; each technique's K/3
// points a Hammersley set shifted by the pixel's own offset (Cranley-Patterson rotation). The
// directions depend on the pixel and a fixed seed, never on the approximation: the measured and the
// approximated images integrate the same directions, so their difference is the BRDFs', not the
// noise's.
#pragma once

#include <cstdint>
#include <vector>

#include "models/geometry.h"

namespace brdfit {

struct EnvironmentOptions {
  // K, sky directions per pixel: a multiple of 3 in [3, 3000]; 0 renders no environment image.
  int samples = 18;
  // The image's N (its own: the sky's K directions cost K evaluations per pixel), in [1, 4096].
  int resolution = 32;
  // The sun: angle from the view direction (+z) and azimuth around it from +x towards +y (up),
  // degrees; irradiance at normal incidence (the sky's zenith radiance is 1). 0 irradiance: no sun.
  double sun_polar_deg = 115;
  double sun_azimuth_deg = 120;
  double sun_irradiance = 3;
  std::uint64_t seed = 1;  // the pixels' offsets (splitmix64 of seed and pixel)
  bool operator==(const EnvironmentOptions&) const = default;
};

// Throws std::invalid_argument (naming the option) outside the ranges above.
void CheckEnvironmentOptions(const EnvironmentOptions& options);

// L_sky of a world direction (unit vector).
double SkyRadiance(const Vec3& world);
// The sun's direction, world space, unit.
Vec3 SunDirection(const EnvironmentOptions& options);

// A direction of a pixel's estimate: wi in the pixel's local frame (z = normal) and the factor
// its f(wi, wo) is multiplied by: L_sky cos / (K p) for a sky direction, E_sun cos for the sun.
struct EnvironmentSample {
  Vec3 wi;
  double weight = 0;
};

// The directions of the pixel (x, y) whose normal n has the tangent frame t, b (world space)
// and whose view direction is wo (local frame). Directions at or below min_cos above the
// horizon are left out (their terms are 0); every weight is finite and positive.
std::vector<EnvironmentSample> EnvironmentSamples(const EnvironmentOptions& options, int x, int y,
                                                  const Vec3& n, const Vec3& t, const Vec3& b,
                                                  const Vec3& wo, double min_cos);

}  // namespace brdfit
