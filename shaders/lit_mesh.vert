#version 330 core
// Lit mesh (OBJ models): model -> world transform, normals to world by the normal matrix.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_diffuse;
uniform mat4 u_viewProjection;
uniform mat4 u_model;
uniform mat3 u_normalMatrix;
out vec3 v_normal;
out vec3 v_diffuse;
void main() {
  v_normal = u_normalMatrix * a_normal;
  v_diffuse = a_diffuse;
  gl_Position = u_viewProjection * u_model * vec4(a_position, 1.0);
}
