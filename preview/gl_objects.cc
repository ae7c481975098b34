#include "preview/gl_objects.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace brdfit::preview {

void CheckGl(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    std::ostringstream s;
    s << "OpenGL error 0x" << std::hex << e << " in " << what;
    throw std::runtime_error(s.str());
  }
}

namespace {

std::string Numbered(const std::string& src) {
  std::istringstream in(src);
  std::ostringstream out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) out << n << ": " << line << "\n";
  return out.str();
}

GLuint Compile(GLenum stage, const std::string& src) {
  const GLuint s = glCreateShader(stage);
  const char* p = src.c_str();
  glShaderSource(s, 1, &p, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<size_t>(std::max(len, 1)), '\0');
    GLsizei written = 0;  // without the terminating NUL, which would cut the message short
    glGetShaderInfoLog(s, len, &written, log.data());
    log.resize(static_cast<size_t>(written));
    glDeleteShader(s);
    throw std::runtime_error(std::string(stage == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                             " shader failed to compile:\n" + log + "\n" + Numbered(src));
  }
  return s;
}

}  // namespace

Program::Program(const std::string& vertex_src, const std::string& fragment_src) {
  const GLuint vs = Compile(GL_VERTEX_SHADER, vertex_src);
  GLuint fs = 0;
  try {
    fs = Compile(GL_FRAGMENT_SHADER, fragment_src);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<size_t>(std::max(len, 1)), '\0');
    GLsizei written = 0;
    glGetProgramInfoLog(id_, len, &written, log.data());
    log.resize(static_cast<size_t>(written));
    glDeleteProgram(id_);
    throw std::runtime_error("shader program failed to link: " +
                             (log.empty() ? std::string("the driver gave no reason") : "\n" + log));
  }
}

Program::~Program() {
  glDeleteProgram(id_);
}

GLint Program::Uniform(const std::string& name) {
  auto it = locations_.find(name);
  if (it != locations_.end()) return it->second;
  const GLint loc = glGetUniformLocation(id_, name.c_str());
  locations_.emplace(name, loc);
  return loc;
}
void Program::Set(const std::string& name, float v) {
  if (GLint l = Uniform(name); l >= 0) glUniform1f(l, v);
}
void Program::Set(const std::string& name, int v) {
  if (GLint l = Uniform(name); l >= 0) glUniform1i(l, v);
}
void Program::Set(const std::string& name, float x, float y) {
  if (GLint l = Uniform(name); l >= 0) glUniform2f(l, x, y);
}
void Program::Set(const std::string& name, float x, float y, float z) {
  if (GLint l = Uniform(name); l >= 0) glUniform3f(l, x, y, z);
}
void Program::SetMat4(const std::string& name, const float* m) {
  if (GLint l = Uniform(name); l >= 0) glUniformMatrix4fv(l, 1, GL_FALSE, m);
}
void Program::SetMat3(const std::string& name, const float* m) {
  if (GLint l = Uniform(name); l >= 0) glUniformMatrix3fv(l, 1, GL_FALSE, m);
}
void Program::SetArray(const std::string& name, const std::vector<float>& v) {
  if (v.empty()) return;
  if (GLint l = Uniform(name + "[0]"); l >= 0) {
    glUniform1fv(l, static_cast<GLsizei>(v.size()), v.data());
  }
}

Framebuffer::Framebuffer(int width, int height) : width_(width), height_(height) {
  glGenTextures(1, &colour_);
  glBindTexture(GL_TEXTURE_2D, colour_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("RGBA32F framebuffer incomplete (status " + std::to_string(status) +
                             ")");
  }
  CheckGl("framebuffer creation");
}

Framebuffer::~Framebuffer() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &depth_);
  glDeleteTextures(1, &colour_);
}

void Framebuffer::Bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
}

Image Framebuffer::ReadRgba() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<float> raw(static_cast<size_t>(width_) * height_ * 4);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, raw.data());
  CheckGl("glReadPixels");
  Image img(width_, height_);
  const size_t row = static_cast<size_t>(width_) * 4;
  for (int y = 0; y < height_; ++y) {
    std::copy_n(raw.begin() + static_cast<std::ptrdiff_t>(row * (height_ - 1 - y)), row,
                img.rgba.begin() + static_cast<std::ptrdiff_t>(row * y));
  }
  return img;
}

GpuMesh::GpuMesh(const std::vector<float>& vertices, const std::vector<int>& attribute_sizes,
                 const std::vector<unsigned>& indices) {
  int stride = 0;
  for (int s : attribute_sizes) stride += s;
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(1, &vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
               vertices.data(), GL_STATIC_DRAW);
  int offset = 0;
  for (size_t i = 0; i < attribute_sizes.size(); ++i) {
    glEnableVertexAttribArray(static_cast<GLuint>(i));
    glVertexAttribPointer(static_cast<GLuint>(i), attribute_sizes[i], GL_FLOAT, GL_FALSE,
                          stride * static_cast<GLsizei>(sizeof(float)),
                          reinterpret_cast<const void*>(offset * sizeof(float)));
    offset += attribute_sizes[i];
  }
  if (!indices.empty()) {
    indexed_ = true;
    glGenBuffers(1, &ebo_);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(indices.size() * sizeof(unsigned)), indices.data(),
                 GL_STATIC_DRAW);
    count_ = static_cast<GLsizei>(indices.size());
  } else {
    count_ = static_cast<GLsizei>(vertices.size() / static_cast<size_t>(stride));
  }
  glBindVertexArray(0);
  CheckGl("mesh upload");
}

GpuMesh::~GpuMesh() {
  glDeleteBuffers(1, &vbo_);
  if (ebo_) glDeleteBuffers(1, &ebo_);
  glDeleteVertexArrays(1, &vao_);
}

void GpuMesh::Draw() const {
  glBindVertexArray(vao_);
  if (indexed_) {
    glDrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
  } else {
    glDrawArrays(GL_TRIANGLES, 0, count_);
  }
  glBindVertexArray(0);
}

Texture::Texture(GLenum target) : target_(target) {
  glGenTextures(1, &id_);
}
Texture::~Texture() {
  glDeleteTextures(1, &id_);
}
void Texture::Bind(int unit) const {
  glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
  glBindTexture(target_, id_);
}

}  // namespace brdfit::preview
