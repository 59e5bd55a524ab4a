// Compiles and links GLSL programs; errors carry the shader file name and the info log.
#include "render/gl/ShaderProgram.hpp"

#include <glad/gl.h>

#include <utility>
#include <vector>

#include "engine/core/Error.hpp"
#include "render/gl/EmbeddedShaders.hpp"

namespace reftrack::render {

namespace {

std::string shaderLog(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return log.data();
}

std::string programLog(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  return log.data();
}

GLuint compile(GLenum type, const std::string& name, const std::string& source) {
  const GLuint shader = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = shaderLog(shader);
    glDeleteShader(shader);
    throw Error("shader " + name + " failed to compile: " + log);
  }
  return shader;
}

}  // namespace

ShaderProgram ShaderProgram::fromFiles(const std::string& vertexFile,
                                       const std::string& fragmentFile) {
  return ShaderProgram("shaders/" + vertexFile, embeddedShaderSource(vertexFile),
                       "shaders/" + fragmentFile, embeddedShaderSource(fragmentFile));
}

ShaderProgram::ShaderProgram(const std::string& vertexName, const std::string& vertexSource,
                             const std::string& fragmentName, const std::string& fragmentSource) {
  const GLuint vertex = compile(GL_VERTEX_SHADER, vertexName, vertexSource);
  GLuint fragment = 0;
  try {
    fragment = compile(GL_FRAGMENT_SHADER, fragmentName, fragmentSource);
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vertex);
  glAttachShader(program_, fragment);
  glLinkProgram(program_);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = programLog(program_);
    glDeleteProgram(program_);
    program_ = 0;
    throw Error("shader program " + vertexName + " + " + fragmentName + " failed to link: " + log);
  }
}

ShaderProgram::~ShaderProgram() {
  if (program_) glDeleteProgram(program_);
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept
    : program_(std::exchange(other.program_, 0)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    if (program_) glDeleteProgram(program_);
    program_ = std::exchange(other.program_, 0);
  }
  return *this;
}

void ShaderProgram::use() const { glUseProgram(program_); }

int ShaderProgram::location(const char* name) const { return glGetUniformLocation(program_, name); }

void ShaderProgram::set(const char* name, int value) const { glUniform1i(location(name), value); }
void ShaderProgram::set(const char* name, float value) const { glUniform1f(location(name), value); }
void ShaderProgram::set(const char* name, const Eigen::Vector2f& value) const {
  glUniform2fv(location(name), 1, value.data());
}
void ShaderProgram::set(const char* name, const Eigen::Vector3f& value) const {
  glUniform3fv(location(name), 1, value.data());
}
void ShaderProgram::set(const char* name, const Eigen::Vector4f& value) const {
  glUniform4fv(location(name), 1, value.data());
}
// Eigen matrices are column-major like GL, so no transpose.
void ShaderProgram::set(const char* name, const Eigen::Matrix3f& value) const {
  glUniformMatrix3fv(location(name), 1, GL_FALSE, value.data());
}
void ShaderProgram::set(const char* name, const Eigen::Matrix4f& value) const {
  glUniformMatrix4fv(location(name), 1, GL_FALSE, value.data());
}

}  // namespace reftrack::render
