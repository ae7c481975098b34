// The GPU preview renderer: draws a scene's objects into an RGBA32F framebuffer (linear
// radiance), then applies the display transform in a second pass. Needs a current OpenGL 3.3
// core context (HeadlessGlContext). Programs and textures are cached across frames.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "preview/explain.h"
#include "preview/gl_objects.h"
#include "core/image.h"
#include "preview/material.h"
#include "preview/scene.h"

namespace brdfit::preview {

class Renderer {
 public:
  Renderer();
  ~Renderer();

  // Linear radiance, alpha = 1 where an object was drawn, 0 elsewhere. width/height <= 0 use
  // the scene's size. Lights that cannot reach an object are culled per object (logged).
  Image RenderLinear(const Scene& scene, const MaterialSet& materials, ExplainLog* log,
                     int width = 0, int height = 0);
  // Display-referred image (background, exposure, tone map, encoding) of a linear image.
  Image ToDisplay(const Image& linear, const Scene& scene);

 private:
  Program& ShadeProgram(const struct ShaderVariant& v, ExplainLog* log);
  // Textures are cached by the object they were made from; the cache co-owns it, so an
  // address is never reused while its texture lives.
  const Texture& TableTexture(const std::shared_ptr<const Table>& table);
  // Texture p (or q) of term `term` (from 0) of a factorization.
  const Texture& FactorTexture(const std::shared_ptr<const FactorTextures>& f, int term, bool q);
  struct CachedTexture {
    std::shared_ptr<const void> owner;
    std::unique_ptr<Texture> texture;
  };
  // Vertex buffers of a mesh, cached (and co-owned) like the textures.
  const GpuMesh& MeshBuffers(const std::shared_ptr<const Mesh>& mesh, ExplainLog* log);
  struct CachedMesh {
    std::shared_ptr<const Mesh> owner;
    std::unique_ptr<GpuMesh> buffers;
  };
  std::map<const Mesh*, CachedMesh> meshes_;
  std::map<std::string, std::unique_ptr<Program>> programs_;
  std::map<const void*, CachedTexture> textures_;
  GLuint empty_vao_ = 0;
};

}  // namespace brdfit::preview
