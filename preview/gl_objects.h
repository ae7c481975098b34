// Small RAII owners of OpenGL objects (one context at a time; the context must be current).
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "preview/gl.h"
#include "core/image.h"

namespace brdfit::preview {

// A linked vertex + fragment program. Compile or link errors throw std::runtime_error with the
// info log and the numbered source, so a generated shader's failure can be read in place.
class Program {
 public:
  Program(const std::string& vertex_src, const std::string& fragment_src);
  ~Program();
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  GLuint id() const { return id_; }
  void Use() const { glUseProgram(id_); }
  // Location cached per name; -1 (uniform absent or optimized out) makes the setters no-ops.
  GLint Uniform(const std::string& name);
  void Set(const std::string& name, float v);
  void Set(const std::string& name, int v);
  void Set(const std::string& name, float x, float y);
  void Set(const std::string& name, float x, float y, float z);
  void SetMat4(const std::string& name, const float* column_major);
  void SetMat3(const std::string& name, const float* column_major);
  void SetArray(const std::string& name, const std::vector<float>& v);

 private:
  GLuint id_ = 0;
  std::unordered_map<std::string, GLint> locations_;
};

// An offscreen render target: RGBA32F colour (linear radiance) + 24-bit depth.
class Framebuffer {
 public:
  Framebuffer(int width, int height);
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  void Bind() const;
  int width() const { return width_; }
  int height() const { return height_; }
  GLuint colour_texture() const { return colour_; }
  // Reads the colour attachment back, top row first (GL's origin is bottom-left).
  Image ReadRgba() const;

 private:
  int width_, height_;
  GLuint fbo_ = 0, colour_ = 0, depth_ = 0;
};

// A vertex array with one interleaved float buffer (attribute i: sizes[i] floats) and
// optional 32-bit indices.
class GpuMesh {
 public:
  GpuMesh(const std::vector<float>& vertices, const std::vector<int>& attribute_sizes,
       const std::vector<unsigned>& indices);
  ~GpuMesh();
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;
  void Draw() const;

 private:
  GLuint vao_ = 0, vbo_ = 0, ebo_ = 0;
  GLsizei count_ = 0;
  bool indexed_ = false;
};

// A texture object owner.
class Texture {
 public:
  explicit Texture(GLenum target);
  ~Texture();
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;
  GLuint id() const { return id_; }
  GLenum target() const { return target_; }
  void Bind(int unit) const;

 private:
  GLenum target_;
  GLuint id_ = 0;
};

}  // namespace brdfit::preview
