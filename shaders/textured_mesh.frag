#version 330 core
// Textured mesh: the texture colour as is (grey textures are swizzled to RGB on upload).
in vec2 v_uv;
uniform sampler2D u_texture;
out vec4 o_colour;
void main() { o_colour = vec4(texture(u_texture, v_uv).rgb, 1.0); }
