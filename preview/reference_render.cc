#include "preview/reference_render.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "models/registry.h"
#include "preview/lights.h"

namespace brdfit::preview {

namespace {

// Ray (o + t d, |d| = 1) against a sphere: the nearer root t > 0 with the stable quadratic
// (Haines et al. 2019, "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems
// ch. 7, eq. 7.5 and 7.7), or +inf. *normal: the outward unit normal at the hit.
double IntersectSphere(const Vec3& centre, double radius, const Vec3& o, const Vec3& d,
                       Vec3* normal) {
  const Vec3 oc = centre - o;
  const double b = Dot(d, oc);
  const Vec3 q = oc - b * d;
  const double disc = radius * radius - Dot(q, q);
  if (disc < 0 || b <= 0) return std::numeric_limits<double>::infinity();
  const double t = (Dot(oc, oc) - radius * radius) / (b + std::sqrt(disc));
  *normal = (1.0 / radius) * (o + t * d - centre);
  return t;
}

// Ray against every triangle (Moller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle
// Intersection", JGT 2(1)), both sides, nearest t in (0, t_max); +inf when none. *normal: the
// barycentric mix of the vertex normals, normalized. Brute force: meshes in tests are small.
double IntersectMesh(const Mesh& m, const Vec3& o, const Vec3& d, double t_max, Vec3* normal) {
  const double inf = std::numeric_limits<double>::infinity();
  // The ray's line passes farther from the bounding sphere's centre than its radius: no hit.
  const Vec3 oc = m.bound_centre - o;
  const Vec3 off_axis = oc - Dot(d, oc) * d;
  const double r = m.bound_radius * (1 + 1e-9);
  if (Dot(off_axis, off_axis) > r * r) return inf;
  double best = t_max;
  bool found = false;
  for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
    const Vec3& p0 = m.positions[m.indices[i]];
    const Vec3 e1 = m.positions[m.indices[i + 1]] - p0, e2 = m.positions[m.indices[i + 2]] - p0;
    const Vec3 pv = Cross(d, e2);
    const double det = Dot(e1, pv);
    if (std::abs(det) < 1e-300) continue;  // ray parallel to the triangle
    const double inv = 1.0 / det;
    const Vec3 tv = o - p0;
    const double u = Dot(tv, pv) * inv;
    if (u < 0 || u > 1) continue;
    const Vec3 qv = Cross(tv, e1);
    const double v = Dot(d, qv) * inv;
    if (v < 0 || u + v > 1) continue;
    const double t = Dot(e2, qv) * inv;
    if (t <= 0 || t >= best) continue;
    best = t;
    found = true;
    const Vec3 mix = (1 - u - v) * m.normals[m.indices[i]] + u * m.normals[m.indices[i + 1]] +
                     v * m.normals[m.indices[i + 2]];
    *normal = Normalize(mix);
  }
  return found ? best : inf;
}

}  // namespace

Image RenderReference(const Scene& scene, const MaterialSet& materials, int width, int height,
                      ReferenceExtras* extras) {
  const Camera& cam = scene.camera;
  // Camera basis in world space (gluLookAt): s right, u up, f forward.
  const Vec3 f = Normalize(cam.target - cam.position);
  const Vec3 s = Normalize(Cross(f, cam.up));
  const Vec3 u = Cross(s, f);
  const double th = std::tan(cam.fov_y / 2), aspect = static_cast<double>(width) / height;

  struct Eval {
    const ModelInfo* model = nullptr;
    const ResolvedMaterial* mat = nullptr;
  };
  std::vector<Eval> evals;
  for (const Object& o : scene.objects) {
    if (o.shape == ObjectShape::kMesh && !o.mesh) {
      throw std::logic_error("object '" + o.name + "': its mesh was not loaded");
    }
    const ResolvedMaterial& m = materials.at(o.material);
    Eval e{nullptr, &m};
    if (m.kind == MaterialKind::kAnalytic) e.model = FindModel(m.model);
    evals.push_back(e);
  }

  Image img(width, height);
  if (extras) {
    extras->cos_view.assign(static_cast<std::size_t>(width) * height, 0.0);
    extras->hit.assign(static_cast<std::size_t>(width) * height, 0);
  }
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double nx = (2.0 * (x + 0.5) / width - 1.0) * th * aspect;
      const double ny = (1.0 - 2.0 * (y + 0.5) / height) * th;
      const Vec3 d = Normalize(nx * s + ny * u + f);
      // Nearest hit over the objects: the normal is the sphere's, or the mesh's vertex normals
      // interpolated at the hit (what the rasterizer's perspective-correct interpolation gives).
      double best = std::numeric_limits<double>::infinity();
      int hit = -1;
      Vec3 n;
      for (std::size_t k = 0; k < scene.objects.size(); ++k) {
        const Object& o = scene.objects[k];
        Vec3 n_k;
        const double t = o.shape == ObjectShape::kMesh
                             ? IntersectMesh(*o.mesh, cam.position, d, best, &n_k)
                             : IntersectSphere(o.centre, o.radius, cam.position, d, &n_k);
        if (t > 0 && t < best) {
          best = t;
          hit = static_cast<int>(k);
          n = n_k;
        }
      }
      if (hit < 0) continue;
      const Vec3 p = cam.position + best * d;
      const Vec3 v = -1.0 * d;
      // Tangent frame: Duff et al. 2017 (JCGT 6(1)), Listing 3, as the shader, but in world
      // space. Analytic and tabulated isotropic BRDFs do not depend on it; a factorization's
      // disk textures do slightly (bilinear filtering of a radial profile is not exactly
      // radial), so both renderers use the same construction.
      // The frame is built from the VIEW-space normal (rows s, u, -f rotate world to view) and
      // rotated back, so it is the shader's frame.
      const Vec3 nv{Dot(s, n), Dot(u, n), -Dot(f, n)};
      const double sg = nv.z >= 0 ? 1.0 : -1.0;
      const double fa = -1.0 / (sg + nv.z), fb = nv.x * nv.y * fa;
      const Vec3 t1v{1.0 + sg * nv.x * nv.x * fa, sg * fb, -sg * nv.x};
      const Vec3 t2v{fb, sg + nv.y * nv.y * fa, -nv.y};
      auto to_world = [&](const Vec3& v) { return v.x * s + v.y * u + (-v.z) * f; };
      const Vec3 t1 = to_world(t1v), t2 = to_world(t2v);
      auto local = [&](const Vec3& w) { return Vec3{Dot(w, t1), Dot(w, t2), Dot(w, n)}; };
      const Vec3 wo = local(v);
      float* out = img.At(x, y);
      out[3] = 1.0f;
      if (extras) {
        extras->hit[static_cast<std::size_t>(y) * width + x] = 1;
        extras->cos_view[static_cast<std::size_t>(y) * width + x] = wo.z;
      }
      if (wo.z <= 0) continue;
      double rgb[3] = {0, 0, 0};
      for (const Light& l : scene.lights) {
        const Incident in = IncidentAt(l, p);
        if (!in.visible) continue;
        const Vec3 wi = local(in.direction);
        if (wi.z <= 0) continue;
        double fr[3] = {0, 0, 0};
        const Eval& e = evals[static_cast<std::size_t>(hit)];
        if (e.model) {
          e.model->eval(e.mat->params.data(), MakeGeometry(wi, wo), fr);
        } else if (e.mat->kind == MaterialKind::kFactored) {
          if (l.type == LightType::kSpot) continue;  // as the GPU's factored path
          const auto v = e.mat->factors->eval(wi, wo);
          for (int c = 0; c < 3; ++c) fr[c] = v[c];
        } else if (auto val = e.mat->table->LookupTrilinear(wi, wo)) {
          for (int c = 0; c < 3; ++c) fr[c] = (*val)[c];
        }
        const double e_scale = wi.z * (scene.punctual_pi ? kPi : 1.0);
        rgb[0] += e_scale * in.colour.x * fr[0];
        rgb[1] += e_scale * in.colour.y * fr[1];
        rgb[2] += e_scale * in.colour.z * fr[2];
      }
      for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(rgb[c]);
    }
  }
  return img;
}

}  // namespace brdfit::preview
