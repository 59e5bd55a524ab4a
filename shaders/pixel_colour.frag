#version 330 core
// Coloured 2-D geometry: per-vertex colour with alpha (blended by the caller).
in vec4 v_colour;
out vec4 o_colour;
void main() { o_colour = v_colour; }
