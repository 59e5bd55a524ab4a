#version 330 core
// Coloured 2-D geometry given in image pixel coordinates (OpenCV convention: pixel centres at
// integers, row 0 at the top), mapped onto the whole viewport.
layout(location = 0) in vec2 a_pixel;
layout(location = 1) in vec4 a_colour;
uniform vec2 u_imageSize;
out vec4 v_colour;
void main() {
  v_colour = a_colour;
  vec2 ndc = vec2(2.0 * (a_pixel.x + 0.5) / u_imageSize.x - 1.0,
                  1.0 - 2.0 * (a_pixel.y + 0.5) / u_imageSize.y);
  gl_Position = vec4(ndc, 0.0, 1.0);
}
