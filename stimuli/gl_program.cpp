#include "stimuli/gl_program.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <vector>

#include "framework/core/error.hpp"

namespace crowdlab::stimuli {
namespace {

GLuint compile(GLenum type, const char* source, const std::string& name) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<size_t>(std::max(length, 1)));
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    throw RuntimeError("GLSL compile error in " + name +
                       (type == GL_VERTEX_SHADER ? " (vertex): " : " (fragment): ") + log.data());
  }
  return shader;
}

}  // namespace

GlProgram::GlProgram(const char* vertex_source, const char* fragment_source, const std::string& name) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex_source, name);
  const GLuint fs = compile(GL_FRAGMENT_SHADER, fragment_source, name);
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<size_t>(std::max(length, 1)));
    glGetProgramInfoLog(id_, length, nullptr, log.data());
    glDeleteProgram(id_);
    throw RuntimeError("GLSL link error in " + name + ": " + log.data());
  }
}

GlProgram::~GlProgram() {
  glDeleteProgram(id_);
}

int GlProgram::uniform(const char* name) {
  auto it = locations_.find(name);
  if (it != locations_.end()) return it->second;
  const int location = glGetUniformLocation(id_, name);
  locations_.emplace(name, location);
  return location;
}

}  // namespace crowdlab::stimuli
