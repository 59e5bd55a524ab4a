#version 330 core
// Textured mesh: world positions through one view-projection matrix (K-exact, see
// render/CameraProjection.hpp).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec2 a_uv;
uniform mat4 u_viewProjection;
out vec2 v_uv;
void main() {
  v_uv = a_uv;
  gl_Position = u_viewProjection * vec4(a_position, 1.0);
}
