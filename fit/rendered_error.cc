#include "fit/rendered_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/luminance.h"
#include "core/rendered_regions.h"

namespace brdfit {
namespace {

// sRGB OETF (IEC 61966-2-1): linear [0, 1] -> encoded [0, 1].
double SrgbOetf(double x) {
  return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

}  // namespace

double RenderedToneMap(double linear, double exposure) {
  return SrgbOetf(std::clamp(exposure * linear, 0.0, 1.0));
}

namespace {

// 10 log10(peak^2 / mse), capped at kRenderedPsnrCapDb (identical images: mse = 0).
double Psnr(double peak, double mse) {
  if (!(mse > 0)) return kRenderedPsnrCapDb;
  return std::min(kRenderedPsnrCapDb, 10.0 * std::log10(peak * peak / mse));
}

// Nearest-rank percentile: the element of 0-based rank min(n - 1, floor(n p / 100)) of the
// sorted values; p = 50 is the upper median, as preview/comparison.cc. Reorders v.
double Percentile(std::vector<double>& v, double p) {
  if (v.empty()) return 0;
  const auto k = std::min(v.size() - 1, static_cast<std::size_t>(std::floor(v.size() * p / 100)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// A pixel of the sphere seen at n.v > min_cos: its normal and tangent frame (world space).
struct SpherePixel {
  int x = 0, y = 0;
  Vec3 n, t, b;
  Vec3 wo;  // v in the local frame
};

// Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin 2017, "Building an Orthonormal
// Basis, Revisited" (JCGT 6(1)), Listing 3: the preview's frame (preview/glsl/common.glsl).
// The camera looks along -z with y up, so world space is the preview's view space.
void BuildFrame(const Vec3& n, Vec3* t, Vec3* b) {
  const double s = n.z >= 0 ? 1.0 : -1.0;
  const double a = -1.0 / (s + n.z), c = n.x * n.y * a;
  *t = {1.0 + s * n.x * n.x * a, s * c, -s * n.x};
  *b = {c, s + n.y * n.y * a, -n.y};
}

// Pixel centre in [-1, 1]^2, row 0 at the top (+y), as an image; true if it is on the sphere.
bool PixelCentre(int x, int y, int res, double* px, double* py) {
  *px = 2.0 * (x + 0.5) / res - 1.0;
  *py = 1.0 - 2.0 * (y + 0.5) / res;
  return *px * *px + *py * *py < 1;
}

// The pixels seen at n.v > min_cos; *on_sphere: every pixel centre on the sphere.
std::vector<SpherePixel> SpherePixels(int res, double min_cos, std::size_t* on_sphere) {
  std::vector<SpherePixel> out;
  *on_sphere = 0;
  const Vec3 v{0, 0, 1};
  for (int y = 0; y < res; ++y) {
    for (int x = 0; x < res; ++x) {
      double px = 0, py = 0;
      if (!PixelCentre(x, y, res, &px, &py)) continue;
      const double r2 = px * px + py * py;
      ++*on_sphere;
      SpherePixel p;
      p.x = x;
      p.y = y;
      p.n = {px, py, std::sqrt(1 - r2)};
      if (!(p.n.z > min_cos)) continue;
      BuildFrame(p.n, &p.t, &p.b);
      p.wo = {Dot(v, p.t), Dot(v, p.b), Dot(v, p.n)};
      out.push_back(p);
    }
  }
  return out;
}

// ok = false with a problem: the metrics are zeroed, the pixel counts kept.
RenderedError Fail(RenderedError r, std::string problem) {
  r.ok = false;
  r.problem = std::move(problem);
  r.psnr_db = r.psnr_srgb_db = r.median_rel_error = r.p95_rel_error = r.peak = r.exposure = 0;
  r.body_color_error = 0;
  for (RenderedLightError& le : r.lights) le.psnr_db = le.median_rel_error = le.p95_rel_error = 0;
  return r;
}

void CheckOptions(const RenderedErrorOptions& o) {
  auto bad = [](const std::string& what) {
    throw std::invalid_argument("rendered error: " + what);
  };
  if (o.resolution < 1 || o.resolution > 4096) bad("resolution must be in [1, 4096]");
  if (o.light_angles_deg.empty() ||
      o.light_angles_deg.size() > static_cast<std::size_t>(kRenderedMaxLights)) {
    bad("1 to " + std::to_string(kRenderedMaxLights) + " lights");
  }
  for (double a : o.light_angles_deg) {
    if (!(a >= 0 && a < 180)) bad("light angles must be in [0, 180) degrees");
  }
  if (!(o.min_cos >= 0 && o.min_cos < 1)) bad("min_cos must be in [0, 1)");
  if (!(o.luminance_floor >= 0 && o.luminance_floor < 1)) bad("luminance_floor must be in [0, 1)");
  if (!(o.exposure_percentile > 0 && o.exposure_percentile <= 100)) {
    bad("exposure_percentile must be in (0, 100]");
  }
  CheckEnvironmentOptions(o.environment);
}

bool Finite3(const std::array<double, 3>& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

}  // namespace

std::size_t RenderedPlan::Bytes() const {
  return sizeof(Pixel) * lit.size() + sizeof(EnvPixel) * env_pixels.size() +
         sizeof(EnvSample) * env_samples.size();
}

RenderedPlan MakeRenderedPlan(const Grid& grid, const RenderedErrorOptions& options) {
  CheckOptions(options);
  RenderedPlan plan;
  plan.grid = grid;
  plan.options = options;
  RenderedError& r = plan.counts;
  r.resolution = options.resolution;
  r.num_lights = static_cast<int>(options.light_angles_deg.size());
  const std::vector<SpherePixel> pixels =
      SpherePixels(options.resolution, options.min_cos, &r.sphere_pixels);
  for (std::size_t k = 0; k < options.light_angles_deg.size(); ++k) {
    const double a = options.light_angles_deg[k] * kPi / 180;
    const Vec3 l{std::sin(a), 0, std::cos(a)};
    r.lights[k].light_deg = options.light_angles_deg[k];
    for (const SpherePixel& p : pixels) {
      const double cos_l = Dot(p.n, l);
      if (!(cos_l > options.min_cos)) continue;
      const Vec3 wi{Dot(l, p.t), Dot(l, p.b), cos_l};
      plan.lit.push_back({wi, p.wo, cos_l, static_cast<int>(k), p.x, p.y,
                          grid.TrilinearTapsAt(RenderedLookupAngles(wi, p.wo))});
    }
  }
  const EnvironmentOptions& env = options.environment;
  if (env.samples > 0) {
    std::size_t env_sphere = 0;
    for (const SpherePixel& p : SpherePixels(env.resolution, options.min_cos, &env_sphere)) {
      RenderedPlan::EnvPixel ep{p.wo, plan.env_samples.size(), 0, p.x, p.y};
      for (const EnvironmentSample& s :
           EnvironmentSamples(env, p.x, p.y, p.n, p.t, p.b, p.wo, options.min_cos)) {
        plan.env_samples.push_back(
            {s.wi, s.weight, grid.TrilinearTapsAt(RenderedLookupAngles(s.wi, p.wo))});
      }
      ep.end = plan.env_samples.size();
      if (ep.end > ep.begin) plan.env_pixels.push_back(ep);
    }
  }
  return plan;
}

RenderedReference PrepareRenderedReference(const Table& measured,
                                           const RenderedErrorOptions& options) {
  return PrepareRenderedReference(measured, MakeRenderedPlan(measured.grid, options));
}

namespace {

// The body's pixels of each region but the rim (RenderedReference::body): the compared pixels
// (Y_m above luminance_floor times the peak Y_m of their light's image, as ScoreRadiances) at or
// below the region's median Y_m (the upper median, as Percentile).
std::array<std::vector<std::size_t>, kRenderedRegions> BodyPixels(const RenderedReference& ref) {
  std::array<std::vector<std::size_t>, kRenderedRegions> compared, body;
  for (int k = 0; k < ref.counts.num_lights; ++k) {
    const auto g = static_cast<std::size_t>(RegionOfLight(ref.counts.lights[k].light_deg));
    if (g == static_cast<std::size_t>(LightRegion::kRim)) continue;
    const double floor_y = ref.luminance_floor * ref.peak_y[static_cast<std::size_t>(k)];
    for (std::size_t i = ref.begin[k]; i < ref.begin[k + 1]; ++i) {
      if (Rec709Luminance(ref.pixels[i].measured.data()) > floor_y) {
        compared[g].push_back(i);
      }
    }
  }
  for (std::size_t g = 0; g < compared.size(); ++g) {
    std::vector<double> y;
    for (const std::size_t i : compared[g])
      y.push_back(Rec709Luminance(ref.pixels[i].measured.data()));
    const double median = Percentile(y, 50);
    for (const std::size_t i : compared[g]) {
      if (Rec709Luminance(ref.pixels[i].measured.data()) <= median) body[g].push_back(i);
    }
  }
  return body;
}

}  // namespace

RenderedReference PrepareRenderedReference(const Table& measured, const RenderedPlan& plan) {
  if (!(plan.grid == measured.grid)) {
    throw std::invalid_argument("rendered error: plan of another grid");
  }
  RenderedReference ref;
  RenderedError& r = ref.counts;
  r = plan.counts;
  ref.luminance_floor = plan.options.luminance_floor;
  ref.exposure_percentile = plan.options.exposure_percentile;
  ref.begin = {0};
  ref.pixels.reserve(plan.lit.size());
  std::size_t p = 0;
  ref.peak_y.assign(static_cast<std::size_t>(r.num_lights), 0.0);
  for (int k = 0; k < r.num_lights; ++k) {
    RenderedLightError& le = r.lights[static_cast<std::size_t>(k)];
    double& peak_y = ref.peak_y[static_cast<std::size_t>(k)];
    for (; p < plan.lit.size() && plan.lit[p].light == k; ++p) {
      const RenderedPlan::Pixel& px = plan.lit[p];
      const auto m = measured.LookupTaps(px.taps);
      if (!m || !Finite3(*m)) {
        ++le.masked_pixels;
        ref.masked.push_back({k, px.x, px.y});
        continue;
      }
      const double c = px.cos_l;
      ref.pixels.push_back({px.wi, px.wo, c, {(*m)[0] * c, (*m)[1] * c, (*m)[2] * c}, px.x,
                            px.y});
      peak_y = std::max(peak_y, Rec709Luminance(ref.pixels.back().measured.data()));
      ++le.lit_pixels;
    }
    ref.begin.push_back(ref.pixels.size());
    r.lit_pixels += le.lit_pixels;
    r.masked_pixels += le.masked_pixels;
  }
  ref.body = BodyPixels(ref);
  for (const RenderedPlan::EnvPixel& ep : plan.env_pixels) {
    RenderedReference::EnvPixel out{ep.wo, {0, 0, 0}, ref.env_samples.size(), 0, ep.x, ep.y};
    for (std::size_t j = ep.begin; j < ep.end; ++j) {
      const RenderedPlan::EnvSample& s = plan.env_samples[j];
      const auto m = measured.LookupTaps(s.taps);
      if (!m || !Finite3(*m)) {
        ++ref.env_masked_samples;
        continue;
      }
      for (int c = 0; c < 3; ++c) out.measured[c] += (*m)[c] * s.weight;
      ref.env_samples.push_back({s.wi, s.weight});
    }
    out.end = ref.env_samples.size();
    if (out.end > out.begin) {
      ref.env_pixels.push_back(out);
      ref.env_peak_y = std::max(ref.env_peak_y, Rec709Luminance(out.measured.data()));
    }
  }
  return ref;
}

namespace {

// Radiances of the lit pixels, light after light: 3 measured then 3 approximated per pixel.
// Empty with *problem set when the approximation is not finite at a lit pixel.
std::vector<double> Radiances(const RenderedReference& ref, const BrdfFunction& approx,
                              std::string* problem) {
  std::vector<double> radiance;
  radiance.reserve(6 * ref.pixels.size());
  for (int k = 0; k < ref.counts.num_lights; ++k) {
    for (std::size_t i = ref.begin[k]; i < ref.begin[k + 1]; ++i) {
      const RenderedReference::Pixel& p = ref.pixels[i];
      const std::array<double, 3> f = approx(p.wi, p.wo);
      if (!Finite3(f)) {
        *problem = "the approximation is not finite at pixel (" + std::to_string(p.x) + ", " +
                   std::to_string(p.y) + ") under the light at " +
                   std::to_string(ref.counts.lights[k].light_deg) + " deg";
        return {};
      }
      for (int c = 0; c < 3; ++c) radiance.push_back(p.measured[c]);
      for (int c = 0; c < 3; ++c) radiance.push_back(f[c] * p.cos_l);
    }
  }
  for (const RenderedReference::EnvPixel& p : ref.env_pixels) {
    std::array<double, 3> sum{};
    for (std::size_t j = p.begin; j < p.end; ++j) {
      const RenderedReference::EnvSample& s = ref.env_samples[j];
      const std::array<double, 3> f = approx(s.wi, p.wo);
      if (!Finite3(f)) {
        *problem = "the approximation is not finite at pixel (" + std::to_string(p.x) + ", " +
                   std::to_string(p.y) + ") of the environment's image";
        return {};
      }
      for (int c = 0; c < 3; ++c) sum[c] += f[c] * s.weight;
    }
    for (int c = 0; c < 3; ++c) radiance.push_back(p.measured[c]);
    for (int c = 0; c < 3; ++c) radiance.push_back(sum[c]);
  }
  return radiance;
}

// The body's colour over one region's body pixels (RenderedReference::body;
// RenderedError::body_color_error): their measured and approximated radiances summed per
// channel, each sum divided by its own luminance (Rec. 709 weights): the body's colour without
// its brightness, which the median luminance error already judges. The largest
// |a_c - m_c| / m_c over the channels; a channel the body hardly has (m_c below 10 % of its
// brightest) is measured against that 10 %: a red body's blue of 0.02 against 0.03 is not a
// colour a viewer sees. 0 without body pixels or when either body is black (a black
// approximation's error is the luminance's to judge).
// L: 6 numbers per pixel (measured RGB, then approximated RGB).
double BodyColorError(const double* L, const std::vector<std::size_t>& body) {
  std::array<double, 3> m{}, a{};
  for (const std::size_t i : body) {
    const double* p = L + 6 * i;
    for (int c = 0; c < 3; ++c) {
      m[c] += p[c];
      a[c] += p[3 + c];
    }
  }
  const double ym = Rec709Luminance(m.data()), ya = Rec709Luminance(a.data());
  if (!(ym > 0) || !(ya > 0)) return 0;
  for (int c = 0; c < 3; ++c) {
    m[c] /= ym;
    a[c] /= ya;
  }
  const double floor = 0.1 * std::max({m[0], m[1], m[2]});
  double worst = 0;
  for (int c = 0; c < 3; ++c)
    worst = std::max(worst, std::abs(a[c] - m[c]) / std::max(m[c], floor));
  return worst;
}

// The metric from the radiances of Radiances(). *pixel_errors (optional): per lit pixel, in the
// reference's order, the relative luminance error |Y_a - Y_m| / Y_m of the metric, NaN where
// the pixel is at or below the floor (not compared).
RenderedError ScoreRadiances(const RenderedReference& ref, const std::vector<double>& radiance,
                             std::vector<double>* pixel_errors) {
  RenderedError r = ref.counts;
  const std::vector<std::size_t>& begin = ref.begin;
  if (pixel_errors) pixel_errors->assign(ref.pixels.size(), std::numeric_limits<double>::quiet_NaN());
  if (r.lit_pixels == 0) {
    return Fail(r, r.masked_pixels ? "every lit pixel's measured lookup is masked"
                                   : "no lit pixel (resolution too small)");
  }
  const double* L = radiance.data();
  double sq_sum = 0;
  std::vector<double> all_errors, all_lum;
  struct RegionSums {
    double sq = 0, peak = 0;
    std::size_t lit = 0;
    std::vector<double> errors;
  };
  std::array<RegionSums, kRenderedRegions> region_sums;
  all_lum.reserve(r.lit_pixels);
  for (int k = 0; k < r.num_lights; ++k) {
    RenderedLightError& le = r.lights[static_cast<std::size_t>(k)];
    const std::string which = "the light at " + std::to_string(le.light_deg) + " deg";
    if (le.lit_pixels == 0) return Fail(r, which + " lights no pixel with a valid measurement");
    // The measured half of L is ref.pixels' measured (Radiances), so ref.peak_y[k] is its peak.
    const double peak_y = ref.peak_y[static_cast<std::size_t>(k)];
    double peak = 0, sq = 0;
    for (std::size_t i = begin[k]; i < begin[k + 1]; ++i) {
      const double* m = L + 6 * i;
      for (int c = 0; c < 3; ++c) {
        peak = std::max(peak, m[c]);
        sq += (m[3 + c] - m[c]) * (m[3 + c] - m[c]);
      }
      all_lum.push_back(Rec709Luminance(m));
    }
    if (!(peak > 0) || !(peak_y > 0)) return Fail(r, which + ": the measured image is black");
    sq_sum += sq;
    r.peak = std::max(r.peak, peak);
    le.psnr_db = Psnr(peak, sq / (3.0 * static_cast<double>(le.lit_pixels)));
    std::vector<double> errors;
    for (std::size_t i = begin[k]; i < begin[k + 1]; ++i) {
      const double* m = L + 6 * i;
      const double ym = Rec709Luminance(m);
      if (!(ym > ref.luminance_floor * peak_y)) continue;
      // |x| / y == |x / y| exactly for y > 0: the signed error's magnitude is the metric's.
      errors.push_back(std::abs(Rec709Luminance(m + 3) - ym) / ym);
      if (pixel_errors) (*pixel_errors)[i] = (Rec709Luminance(m + 3) - ym) / ym;
    }
    le.compared_pixels = errors.size();
    r.compared_pixels += errors.size();
    const auto g = static_cast<std::size_t>(RegionOfLight(le.light_deg));
    RegionSums& rs = region_sums[g];
    ++r.regions[g].lights;
    rs.sq += sq;
    rs.peak = std::max(rs.peak, peak);
    rs.lit += le.lit_pixels;
    rs.errors.insert(rs.errors.end(), errors.begin(), errors.end());
    all_errors.insert(all_errors.end(), errors.begin(), errors.end());
    le.median_rel_error = Percentile(errors, 50);
    le.p95_rel_error = Percentile(errors, 95);
  }
  for (std::size_t g = 0; g < region_sums.size(); ++g) {
    if (r.regions[g].lights == 0) continue;
    RegionSums& rs = region_sums[g];
    r.regions[g].psnr_db = Psnr(rs.peak, rs.sq / (3.0 * static_cast<double>(rs.lit)));
    r.regions[g].median_rel_error = Percentile(rs.errors, 50);
    // ref.body holds no rim pixels: the rim's dim pixels are grazing and whiten with the
    // specular's Fresnel rise (docs/accuracy.md, "The body's colour").
    r.body_color_error = std::max(r.body_color_error, BodyColorError(L, ref.body[g]));
  }
  // The environment's image (its pixels follow the lights'): a region of its own, judged as the
  // lights' regions are; not pooled into the whole metric.
  if (!ref.env_pixels.empty()) {
    const double* E = L + 6 * ref.pixels.size();
    const std::size_t n = ref.env_pixels.size();
    const double peak_y = ref.env_peak_y;
    double peak = 0, sq = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double* m = E + 6 * i;
      for (int c = 0; c < 3; ++c) {
        peak = std::max(peak, m[c]);
        sq += (m[3 + c] - m[c]) * (m[3 + c] - m[c]);
      }
    }
    if (!(peak > 0) || !(peak_y > 0)) return Fail(r, "the environment's measured image is black");
    std::vector<double> errors;
    for (std::size_t i = 0; i < n; ++i) {
      const double* m = E + 6 * i;
      const double ym = Rec709Luminance(m);
      if (ym > ref.luminance_floor * peak_y)
        errors.push_back(std::abs(Rec709Luminance(m + 3) - ym) / ym);
    }
    RenderedRegionError& g = r.regions[static_cast<std::size_t>(LightRegion::kEnvironment)];
    g.lights = 1;
    g.psnr_db = Psnr(peak, sq / (3.0 * static_cast<double>(n)));
    g.median_rel_error = Percentile(errors, 50);
  }
  r.below_floor_pixels = r.lit_pixels - r.compared_pixels;
  r.psnr_db = Psnr(r.peak, sq_sum / (3.0 * static_cast<double>(r.lit_pixels)));
  r.median_rel_error = Percentile(all_errors, 50);
  r.p95_rel_error = Percentile(all_errors, 95);

  // Tone-mapped sRGB PSNR: exposure from the measured luminance percentile, clamp to [0, 1],
  // sRGB OETF, peak 1 (not quantized to 8 bits).
  const double y_ref = Percentile(all_lum, ref.exposure_percentile);
  if (!(y_ref > 0)) {
    return Fail(r, "the measured luminance's " + std::to_string(ref.exposure_percentile) +
                       "th percentile is not positive");
  }
  r.exposure = 1.0 / y_ref;
  double sq_t = 0;
  for (std::size_t i = 0; i < r.lit_pixels; ++i) {
    const double* m = L + 6 * i;
    for (int c = 0; c < 3; ++c) {
      const double d = RenderedToneMap(m[3 + c], r.exposure) - RenderedToneMap(m[c], r.exposure);
      sq_t += d * d;
    }
  }
  r.psnr_srgb_db = Psnr(1.0, sq_t / (3.0 * static_cast<double>(r.lit_pixels)));

  // Every number finite, or the reason (a huge approximation overflows the squared error).
  bool finite = std::isfinite(r.psnr_db) && std::isfinite(r.psnr_srgb_db) &&
                std::isfinite(r.median_rel_error) && std::isfinite(r.p95_rel_error) &&
                std::isfinite(r.exposure) && std::isfinite(r.peak);
  for (int k = 0; k < r.num_lights; ++k) {
    const RenderedLightError& le = r.lights[static_cast<std::size_t>(k)];
    finite = finite && std::isfinite(le.psnr_db) && std::isfinite(le.median_rel_error) &&
             std::isfinite(le.p95_rel_error);
  }
  for (const RenderedRegionError& g : r.regions) {
    finite = finite && std::isfinite(g.psnr_db) && std::isfinite(g.median_rel_error);
  }
  finite = finite && std::isfinite(r.body_color_error);
  if (!finite) return Fail(r, "an error overflows (the approximation is too large)");
  r.ok = true;
  return r;
}

}  // namespace

RenderedError ScoreRendered(const RenderedReference& ref, const BrdfFunction& approx) {
  std::string problem;
  const std::vector<double> radiance = Radiances(ref, approx, &problem);
  if (!problem.empty()) return Fail(ref.counts, problem);
  return ScoreRadiances(ref, radiance, nullptr);
}

RenderedImages RenderImages(const RenderedReference& ref, const BrdfFunction& approx) {
  RenderedImages out;
  std::string problem;
  const std::vector<double> radiance = Radiances(ref, approx, &problem);
  if (!problem.empty()) {
    out.metric = Fail(ref.counts, problem);
    return out;
  }
  std::vector<double> signed_errors;
  out.metric = ScoreRadiances(ref, radiance, &signed_errors);
  const int res = ref.counts.resolution;
  const auto n2 = static_cast<std::size_t>(res) * static_cast<std::size_t>(res);
  using State = RenderedImage::State;
  for (int k = 0; k < ref.counts.num_lights; ++k) {
    RenderedImage img;
    img.light_deg = ref.counts.lights[static_cast<std::size_t>(k)].light_deg;
    img.resolution = res;
    img.state.assign(n2, State::kOff);
    img.measured.assign(3 * n2, 0.0);
    img.approx.assign(3 * n2, 0.0);
    img.rel_error.assign(n2, std::numeric_limits<double>::quiet_NaN());
    for (int y = 0; y < res; ++y) {
      for (int x = 0; x < res; ++x) {
        double px = 0, py = 0;
        if (PixelCentre(x, y, res, &px, &py)) img.state[static_cast<std::size_t>(y) * res + x] = State::kUnlit;
      }
    }
    for (const RenderedReference::Masked& m : ref.masked) {
      if (m.light == k) img.state[static_cast<std::size_t>(m.y) * res + m.x] = State::kMasked;
    }
    for (std::size_t i = ref.begin[k]; i < ref.begin[k + 1]; ++i) {
      const RenderedReference::Pixel& p = ref.pixels[i];
      const std::size_t at = static_cast<std::size_t>(p.y) * res + p.x;
      for (int c = 0; c < 3; ++c) {
        img.measured[3 * at + c] = radiance[6 * i + c];
        img.approx[3 * at + c] = radiance[6 * i + 3 + c];
      }
      img.rel_error[at] = signed_errors[i];
      img.state[at] = std::isnan(signed_errors[i]) ? State::kBelowFloor : State::kCompared;
    }
    out.lights.push_back(std::move(img));
  }
  return out;
}

RenderedError ComputeRenderedError(const Table& measured, const BrdfFunction& approx,
                                   const RenderedErrorOptions& options) {
  return ScoreRendered(PrepareRenderedReference(measured, options), approx);
}

BrdfFunction ModelBrdf(const ModelInfo& model, std::vector<double> params) {
  return [eval = model.eval, p = std::move(params)](const Vec3& wi, const Vec3& wo) {
    std::array<double, 3> rgb{};
    eval(p.data(), MakeGeometry(wi, wo), rgb.data());
    return rgb;
  };
}

}  // namespace brdfit

namespace brdfit {

HalfDiffAngles RenderedLookupAngles(const Vec3& wi, const Vec3& wo) {
  HalfDiffAngles a = ToHalfDiff(wi, wo);
  if (a.theta_d < 1e-6) a.phi_d = 0;
  return a;
}

std::optional<std::array<double, 3>> RenderedLookup(const Table& table, const Vec3& wi,
                                                    const Vec3& wo) {
  return table.LookupTrilinear(RenderedLookupAngles(wi, wo));
}

BrdfFunction TableBrdf(const Table& table) {
  return [&table](const Vec3& wi, const Vec3& wo) {
    const auto v = RenderedLookup(table, wi, wo);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return v ? *v : std::array<double, 3>{nan, nan, nan};
  };
}

}  // namespace brdfit
