#include "fit/rendered_environment.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace brdfit {
namespace {

constexpr double kSkyRoughness[2] = {0.3, 0.03};

// splitmix64 (Steele, Lea, Flood 2014, "Fast splittable pseudorandom number generators"): the
// finalizer of Java's SplittableRandom, a bijection that mixes every input bit.
std::uint64_t SplitMix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A number in [0, 1) from 53 bits of the hash.
double Uniform(std::uint64_t h) {
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

// The radical inverse of i in base 2 (van der Corput): its bits mirrored about the point.
double RadicalInverse2(std::uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
  return static_cast<double>(i) * 0x1.0p-32;
}

// The GGX distribution of normals (Walter et al. 2007, Eq. 33) at cos theta_h = c > 0.
double GgxD(double c, double alpha) {
  const double c2 = c * c, a2 = alpha * alpha;
  const double tan2 = (1 - c2) / c2;
  return a2 / (kPi * c2 * c2 * (a2 + tan2) * (a2 + tan2));
}

// The density over directions wi of the half-vector technique of roughness alpha: the half
// vector drawn with density D(h) cos theta_h (Walter et al. 2007, Eqs. 35-36), wi its
// reflection of wo, so p(wi) = D(h) cos theta_h / (4 |wo.h|) (Eq. 38 with the reflection's
// Jacobian, Eq. 14). wi and wo unit, local frame.
double HalfVectorPdf(const Vec3& wi, const Vec3& wo, double alpha) {
  Vec3 h = wi + wo;
  const double len = std::sqrt(Dot(h, h));
  if (!(len > 0)) return 0;
  h = (1 / len) * h;
  if (!(h.z > 0)) return 0;
  const double oh = std::abs(Dot(wo, h));
  if (!(oh > 0)) return 0;
  return GgxD(h.z, alpha) * h.z / (4 * oh);
}

// The mixture's density (balance heuristic with equal counts).
double MixturePdf(const Vec3& wi, const Vec3& wo) {
  double p = wi.z > 0 ? wi.z / kPi : 0;
  for (const double a : kSkyRoughness) p += HalfVectorPdf(wi, wo, a);
  return p / 3;
}

}  // namespace

void CheckEnvironmentOptions(const EnvironmentOptions& o) {
  auto bad = [](const std::string& what) {
    throw std::invalid_argument("rendered error: environment " + what);
  };
  if (o.samples != 0 && (o.samples < 3 || o.samples > 3000 || o.samples % 3 != 0)) {
    bad("samples must be 0 or a multiple of 3 in [3, 3000]");
  }
  if (o.resolution < 1 || o.resolution > 4096) bad("resolution must be in [1, 4096]");
  if (!(o.sun_polar_deg >= 0 && o.sun_polar_deg <= 180)) bad("sun polar angle must be in [0, 180]");
  if (!std::isfinite(o.sun_azimuth_deg)) bad("sun azimuth must be finite");
  if (!(o.sun_irradiance >= 0 && o.sun_irradiance <= 1e6)) {
    bad("sun irradiance must be in [0, 1e6]");
  }
}

double SkyRadiance(const Vec3& w) {
  return w.y >= 0 ? 0.25 + 0.75 * w.y : 0.1;
}

Vec3 SunDirection(const EnvironmentOptions& o) {
  const double p = o.sun_polar_deg * kPi / 180, a = o.sun_azimuth_deg * kPi / 180;
  return {std::sin(p) * std::cos(a), std::sin(p) * std::sin(a), std::cos(p)};
}

std::vector<EnvironmentSample> EnvironmentSamples(const EnvironmentOptions& o, int x, int y,
                                                  const Vec3& n, const Vec3& t, const Vec3& b,
                                                  const Vec3& wo, double min_cos) {
  std::vector<EnvironmentSample> out;
  const int k = o.samples;
  const std::uint64_t pixel = SplitMix64(
      o.seed ^ SplitMix64((static_cast<std::uint64_t>(y) << 32) | static_cast<std::uint32_t>(x)));
  const int per = k / 3;
  // Per technique, the points of a Hammersley set of K / 3 points (Hammersley & Handscomb 1964;
  // Pharr, Jakob, Humphreys, PBR 4th ed., Sec. 8.6) shifted by the pixel's own random offset
  // modulo 1 (Cranley & Patterson 1976): evenly spread in both dimensions, so a smooth sky
  // converges far faster than at independent points, and no two pixels share directions.
  std::array<double, 6> shift{};
  for (int c = 0; c < 6; ++c) shift[c] = Uniform(SplitMix64(pixel + static_cast<std::uint64_t>(c)));
  for (int j = 0; j < k; ++j) {
    const int technique = j % 3, i = j / 3;
    double u1 = (i + 0.5) / per + shift[2 * technique];
    double u2 = RadicalInverse2(static_cast<std::uint32_t>(i)) + shift[2 * technique + 1];
    u1 -= std::floor(u1);
    u2 -= std::floor(u2);
    const double phi = 2 * kPi * u2;
    Vec3 wi;
    if (technique == 0) {
      // Malley's method: a uniform point of the unit disc lifted to the hemisphere.
      const double r = std::sqrt(u1);
      wi = {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u1))};
    } else {
      const double alpha = kSkyRoughness[technique - 1];
      // Walter et al. 2007, Eq. 35: tan theta_h = alpha sqrt(u1 / (1 - u1)).
      const double tan_h = alpha * std::sqrt(u1 / std::max(1e-300, 1 - u1));
      const double ch = 1 / std::sqrt(1 + tan_h * tan_h), sh = tan_h * ch;
      const Vec3 h{sh * std::cos(phi), sh * std::sin(phi), ch};
      const double oh = Dot(wo, h);
      wi = (2 * oh) * h - wo;  // Eq. 39, the reflection of wo about h
    }
    if (!(wi.z > min_cos)) continue;
    const double p = MixturePdf(wi, wo);
    if (!(p > 0) || !std::isfinite(p)) continue;
    const Vec3 world = wi.x * t + wi.y * b + wi.z * n;
    const double w = SkyRadiance(world) * wi.z / (k * p);
    if (!(w > 0) || !std::isfinite(w)) continue;
    out.push_back({wi, w});
  }
  if (o.sun_irradiance > 0) {
    const Vec3 l = SunDirection(o);
    const Vec3 wi{Dot(l, t), Dot(l, b), Dot(l, n)};
    if (wi.z > min_cos) out.push_back({wi, o.sun_irradiance * wi.z});
  }
  return out;
}

}  // namespace brdfit
