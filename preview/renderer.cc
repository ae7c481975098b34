#include "preview/renderer.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/error.h"
#include "preview/camera_math.h"
#include "preview/lights.h"
#include "preview/shader_gen.h"

namespace brdfit::preview {
namespace {

// NDC rectangle bounding the projection of a sphere: the projected corners of its bounding
// cube, or the whole viewport if a corner is behind the near plane.
std::array<float, 4> SphereRect(const Eigen::Matrix4d& view, const Eigen::Matrix4d& proj,
                                const Vec3& centre, double radius, double near) {
  double x0 = 1, y0 = 1, x1 = -1, y1 = -1;
  const double r = radius * 1.001;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner{centre.x + (i & 1 ? r : -r), centre.y + (i & 2 ? r : -r),
                      centre.z + (i & 4 ? r : -r)};
    const Vec3 v = Transform(view, corner, 1.0);
    if (-v.z <= near) return {-1, -1, 1, 1};
    const Eigen::Vector4d c = proj * Eigen::Vector4d(v.x, v.y, v.z, 1.0);
    x0 = std::min(x0, c.x() / c.w());
    x1 = std::max(x1, c.x() / c.w());
    y0 = std::min(y0, c.y() / c.w());
    y1 = std::max(y1, c.y() / c.w());
  }
  auto cl = [](double v) { return static_cast<float>(std::clamp(v, -1.0, 1.0)); };
  return {cl(x0), cl(y0), cl(x1), cl(y1)};
}

Vec3 Scaled(const Light& l) {
  return l.intensity * l.colour;
}

// The lights reaching an object are uniform arrays of its fragment shader: beyond the GL's
// uniform space the program fails to link, and Mesa says no more than that (5,000 lights).
// Refused first, with the limit: vec4 slots per light at worst (a vec3 or
// a float takes a whole slot), 64 slots kept for the material's and camera's uniforms.
void CheckLightUniforms(const std::string& object, std::size_t dir, std::size_t point,
                        std::size_t spot) {
  GLint components = 0;
  glGetIntegerv(GL_MAX_FRAGMENT_UNIFORM_COMPONENTS, &components);
  const long slots = components / 4 - 64;
  const auto need = static_cast<long>(2 * dir + 4 * point + 7 * spot);
  if (components <= 0 || need <= slots) return;
  throw InputError(fmt::format(
      "object '{}': {} lights reach it ({} directional, {} point, {} spot), more than this "
      "OpenGL's fragment shaders hold: at most about {} directional or {} point or {} spot lights "
      "(GL_MAX_FRAGMENT_UNIFORM_COMPONENTS = {})",
      object, dir + point + spot, dir, point, spot, slots / 2, slots / 4, slots / 7, components));
}

}  // namespace

Renderer::Renderer() {
  glGenVertexArrays(1, &empty_vao_);
  CheckGl("renderer setup");
}

Renderer::~Renderer() {
  glDeleteVertexArrays(1, &empty_vao_);
}

Program& Renderer::ShadeProgram(const ShaderVariant& v, ExplainLog* log) {
  const std::string key = v.Key();
  auto it = programs_.find(key);
  if (it != programs_.end()) {
    if (log) log->Add("reuse", "shader [" + key + "]");
    return *it->second;
  }
  if (log) log->Add("compute", "shader [" + key + "]");
  auto p = std::make_unique<Program>(ShadeVertexSource(v), ShadeFragmentSource(v));
  return *programs_.emplace(key, std::move(p)).first->second;
}

const Texture& Renderer::TableTexture(const std::shared_ptr<const Table>& owner) {
  auto it = textures_.find(owner.get());
  if (it != textures_.end()) return *it->second.texture;
  const Table& table = *owner;
  const Grid& g = table.grid;
  // Texels (rgb * valid, valid), phi_d fastest: the table's own index layout.
  std::vector<float> texels(4 * g.NumCells());
  for (std::size_t i = 0; i < g.NumCells(); ++i) {
    const float v = table.valid[i] ? 1.0f : 0.0f;
    for (int c = 0; c < 3; ++c) {
      texels[4 * i + c] = v > 0 ? static_cast<float>(table.rgb[3 * i + c]) : 0.0f;
    }
    texels[4 * i + 3] = v;
  }
  auto tex = std::make_unique<Texture>(GL_TEXTURE_3D);
  tex->Bind(0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA32F, g.n_phi_d, g.n_theta_d, g.n_theta_h, 0, GL_RGBA,
               GL_FLOAT, texels.data());
  // The shader filters (preview/glsl/texel_filter.glsl, texelFetch): the unit samples nothing.
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_REPEAT);  // phi_d: period pi
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  CheckGl("table texture upload");
  return *textures_.emplace(owner.get(), CachedTexture{owner, std::move(tex)})
              .first->second.texture;
}

const Texture& Renderer::FactorTexture(const std::shared_ptr<const FactorTextures>& f, int term,
                                       bool q) {
  const Image& img = q ? f->terms.at(static_cast<std::size_t>(term)).q
                       : f->terms.at(static_cast<std::size_t>(term)).p;
  auto it = textures_.find(&img);
  if (it != textures_.end()) return *it->second.texture;
  auto tex = std::make_unique<Texture>(GL_TEXTURE_2D);
  tex->Bind(0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, img.width, img.height, 0, GL_RGBA, GL_FLOAT,
               img.rgba.data());
  // The shader filters (preview/glsl/texel_filter.glsl, texelFetch): the unit samples nothing.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  // Disk maps clamp; the (theta_d, phi_d) rectangle of halfdiff's q repeats in phi_d (rows).
  const bool wrap_rows = q && f->parameterization == "halfdiff";
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap_rows ? GL_REPEAT : GL_CLAMP_TO_EDGE);
  CheckGl("factor texture upload");
  return *textures_.emplace(&img, CachedTexture{f, std::move(tex)}).first->second.texture;
}

const GpuMesh& Renderer::MeshBuffers(const std::shared_ptr<const Mesh>& mesh, ExplainLog* log) {
  auto it = meshes_.find(mesh.get());
  if (it != meshes_.end()) return *it->second.buffers;
  // Interleaved position, normal (attributes 0 and 1 of object.vert), world space.
  std::vector<float> vertices;
  vertices.reserve(6 * mesh->positions.size());
  for (std::size_t i = 0; i < mesh->positions.size(); ++i) {
    const Vec3& p = mesh->positions[i];
    const Vec3& n = mesh->normals[i];
    for (double x : {p.x, p.y, p.z, n.x, n.y, n.z}) vertices.push_back(static_cast<float>(x));
  }
  auto buffers = std::make_unique<GpuMesh>(vertices, std::vector<int>{3, 3}, mesh->indices);
  CheckGl("mesh upload");
  if (log)
    log->Add("compute", "vertex buffers (" + std::to_string(mesh->NumTriangles()) + " triangles)");
  return *meshes_.emplace(mesh.get(), CachedMesh{mesh, std::move(buffers)}).first->second.buffers;
}

Image Renderer::RenderLinear(const Scene& scene, const MaterialSet& materials, ExplainLog* log,
                             int width, int height) {
  if (width <= 0) width = scene.width;
  if (height <= 0) height = scene.height;
  const Eigen::Matrix4d view = ViewMatrix(scene.camera);
  const Eigen::Matrix4d proj = ProjectionMatrix(scene.camera, static_cast<double>(width) / height);
  const Eigen::Matrix4f projf = proj.cast<float>();
  const double th = std::tan(scene.camera.fov_y / 2);

  Framebuffer fbo(width, height);
  fbo.Bind();
  glClearColor(0, 0, 0, 0);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glBindVertexArray(empty_vao_);

  for (const Object& obj : scene.objects) {
    auto mit = materials.find(obj.material);
    if (mit == materials.end()) {
      throw std::logic_error("material '" + obj.material + "' was not resolved");
    }
    const ResolvedMaterial& mat = mit->second;
    const bool is_mesh = obj.shape == ObjectShape::kMesh;
    if (is_mesh && !obj.mesh) {  // LoadScene / LoadSceneMeshes were not called
      throw std::logic_error("object '" + obj.name + "': its mesh was not loaded");
    }
    // Lights that reach this object; the rest are culled before the shader is generated.
    std::vector<const Light*> dir, point, spot;
    for (const Light& l : scene.lights) {
      std::string why;
      if (!LightReachesSphere(l, obj.BoundCentre(), obj.BoundRadius(), &why)) {
        if (log) log->Add("skip", "light '" + l.name + "' for object '" + obj.name + "': " + why);
        continue;
      }
      if (mat.kind == MaterialKind::kFactored && l.type == LightType::kSpot) {
        // The factored path: point and directional lights, two fetches per light and term.
        if (log) {
          log->Add("skip", "spot light '" + l.name + "' for object '" + obj.name +
                               "': the factored path supports point and directional lights "
                               "only");
        }
        continue;
      }
      (l.type == LightType::kDirectional ? dir
       : l.type == LightType::kPoint     ? point
                                         : spot)
          .push_back(&l);
    }
    CheckLightUniforms(obj.name, dir.size(), point.size(), spot.size());
    ShaderVariant v;
    v.material = mat.kind;
    v.model = mat.model;
    if (mat.table) v.theta_h_mapping = mat.table->grid.theta_h_mapping;
    if (mat.factors) {
      v.factor_param = mat.factors->parameterization;
      v.factor_rank = mat.factors->rank();
    }
    v.num_directional = static_cast<int>(dir.size());
    v.num_point = static_cast<int>(point.size());
    v.num_spot = static_cast<int>(spot.size());
    v.punctual_pi = scene.punctual_pi;
    v.mesh = is_mesh;
    Program& prog = ShadeProgram(v, log);
    prog.Use();

    prog.Set("uViewport", static_cast<float>(width), static_cast<float>(height));
    prog.Set("uTanHalfFov", static_cast<float>(th * width / height), static_cast<float>(th));
    prog.SetMat4("uProjection", projf.data());
    if (is_mesh) {
      // World-space vertices: the model-view matrix is the view; its rotation (orthonormal)
      // is its own inverse transpose, Three.js's normal matrix.
      const Eigen::Matrix4f viewf = view.cast<float>();
      const Eigen::Matrix3f normal_matrix = viewf.topLeftCorner<3, 3>();
      prog.SetMat4("uModelView", viewf.data());
      prog.SetMat3("uNormalMatrix", normal_matrix.data());
    } else {
      const Vec3 c = Transform(view, obj.centre, 1.0);
      prog.Set("uSphereCentre", static_cast<float>(c.x), static_cast<float>(c.y),
               static_cast<float>(c.z));
      prog.Set("uSphereRadius", static_cast<float>(obj.radius));
      const auto rect = SphereRect(view, proj, obj.centre, obj.radius, scene.camera.near);
      if (GLint l = prog.Uniform("uRect"); l >= 0)
        glUniform4f(l, rect[0], rect[1], rect[2], rect[3]);
    }

    auto set3 = [&](const std::string& n, const Vec3& x) {
      prog.Set(n, static_cast<float>(x.x), static_cast<float>(x.y), static_cast<float>(x.z));
    };
    for (std::size_t i = 0; i < dir.size(); ++i) {
      const std::string p = "directionalLights[" + std::to_string(i) + "].";
      set3(p + "direction", Normalize(Transform(view, Normalize(dir[i]->direction), 0.0)));
      set3(p + "color", Scaled(*dir[i]));
    }
    for (std::size_t i = 0; i < point.size(); ++i) {
      const std::string p = "pointLights[" + std::to_string(i) + "].";
      set3(p + "position", Transform(view, point[i]->position, 1.0));
      set3(p + "color", Scaled(*point[i]));
      prog.Set(p + "distance", static_cast<float>(point[i]->distance));
      prog.Set(p + "decay", static_cast<float>(point[i]->decay));
    }
    for (std::size_t i = 0; i < spot.size(); ++i) {
      const Light& s = *spot[i];
      const std::string p = "spotLights[" + std::to_string(i) + "].";
      set3(p + "position", Transform(view, s.position, 1.0));
      set3(p + "direction", Normalize(Transform(view, s.position - s.target, 0.0)));
      set3(p + "color", Scaled(s));
      prog.Set(p + "distance", static_cast<float>(s.distance));
      prog.Set(p + "decay", static_cast<float>(s.decay));
      prog.Set(p + "coneCos", static_cast<float>(std::cos(s.angle)));
      prog.Set(p + "penumbraCos", static_cast<float>(std::cos(s.angle * (1 - s.penumbra))));
    }
    switch (mat.kind) {
      case MaterialKind::kAnalytic: {
        std::vector<float> p(mat.params.begin(), mat.params.end());
        prog.SetArray("uParams", p);
        break;
      }
      case MaterialKind::kMeasured:
        TableTexture(mat.table).Bind(0);
        prog.Set("uTable", 0);
        break;
      case MaterialKind::kFactored: {
        // Term k's p and q on units 2k + 1 and 2k + 2 (unit 0 is the tables'), named as in
        // preview/glsl/factored.glsl: uFactorP, uFactorQ, uFactorP2, uFactorQ2, ...
        const FactorTextures& f = *mat.factors;
        for (int k = 0; k < f.rank(); ++k) {
          const std::string n = k == 0 ? "" : std::to_string(k + 1);
          FactorTexture(mat.factors, k, false).Bind(2 * k + 1);
          FactorTexture(mat.factors, k, true).Bind(2 * k + 2);
          prog.Set("uFactorP" + n, 2 * k + 1);
          prog.Set("uFactorQ" + n, 2 * k + 2);
        }
        prog.Set("uFactorDiffuse", static_cast<float>(f.diffuse.x), static_cast<float>(f.diffuse.y),
                 static_cast<float>(f.diffuse.z));
        break;
      }
    }
    if (is_mesh) {
      MeshBuffers(obj.mesh, log).Draw();
      glBindVertexArray(empty_vao_);
    } else {
      glDrawArrays(GL_TRIANGLES, 0, 6);
    }
    CheckGl("draw");
    if (log) {
      log->Add("draw", "object '" + obj.name + "' (" + ToString(mat.kind) + " '" + mat.name +
                           "', " + std::to_string(dir.size() + point.size() + spot.size()) +
                           " light(s))");
    }
  }
  glBindVertexArray(0);
  return fbo.ReadRgba();
}

Image Renderer::ToDisplay(const Image& linear, const Scene& scene) {
  const DisplaySettings& d = scene.display;
  const std::string key =
      std::string("tonemap ") + ToString(d.tone_map) + " " + ToString(d.encoding);
  auto it = programs_.find(key);
  if (it == programs_.end()) {
    it = programs_
             .emplace(key, std::make_unique<Program>(FullscreenVertexSource(),
                                                     ToneMapFragmentSource(d.tone_map, d.encoding)))
             .first;
  }
  Program& prog = *it->second;
  Framebuffer fbo(linear.width, linear.height);  // before binding the source: it binds a texture
  Texture src(GL_TEXTURE_2D);
  src.Bind(0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // Upload bottom row first (GL origin).
  std::vector<float> flipped(linear.rgba.size());
  const std::size_t row = 4 * static_cast<std::size_t>(linear.width);
  for (int y = 0; y < linear.height; ++y) {
    std::copy_n(linear.At(0, linear.height - 1 - y), row, flipped.begin() + row * y);
  }
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, linear.width, linear.height, 0, GL_RGBA, GL_FLOAT,
               flipped.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  fbo.Bind();
  glDisable(GL_DEPTH_TEST);
  prog.Use();
  prog.Set("uLinear", 0);
  prog.Set("toneMappingExposure", static_cast<float>(d.exposure));
  prog.Set("toneMappingWhitePoint", static_cast<float>(d.white_point));
  prog.Set("uBackground", static_cast<float>(scene.background.x),
           static_cast<float>(scene.background.y), static_cast<float>(scene.background.z));
  glBindVertexArray(empty_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  CheckGl("tone map pass");
  return fbo.ReadRgba();
}

}  // namespace brdfit::preview
