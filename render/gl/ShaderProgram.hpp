#pragma once
// ShaderProgram: a linked GLSL vertex + fragment program. Compile and link failures throw
// reftrack::Error naming the shader file and quoting the GL info log. Needs a current context.
#include <Eigen/Core>
#include <string>

namespace reftrack::render {

class ShaderProgram {
 public:
  // From the embedded shaders/<vertexFile> and shaders/<fragmentFile>.
  static ShaderProgram fromFiles(const std::string& vertexFile, const std::string& fragmentFile);
  // From source text; the names only label error messages.
  ShaderProgram(const std::string& vertexName, const std::string& vertexSource,
                const std::string& fragmentName, const std::string& fragmentSource);
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  void use() const;
  unsigned int id() const { return program_; }

  // Uniform setters (the program must be in use); a name the linker optimised away is ignored.
  void set(const char* name, int value) const;
  void set(const char* name, float value) const;
  void set(const char* name, const Eigen::Vector2f& value) const;
  void set(const char* name, const Eigen::Vector3f& value) const;
  void set(const char* name, const Eigen::Vector4f& value) const;
  void set(const char* name, const Eigen::Matrix3f& value) const;
  void set(const char* name, const Eigen::Matrix4f& value) const;

 private:
  int location(const char* name) const;
  unsigned int program_ = 0;
};

}  // namespace reftrack::render
