#version 330 core
// Video background: texture row 0 (image top) at the top of the viewport.
in vec2 v_uv;
uniform sampler2D u_image;
out vec4 o_colour;
void main() { o_colour = vec4(texture(u_image, v_uv).rgb, 1.0); }
