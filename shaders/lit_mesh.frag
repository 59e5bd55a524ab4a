#version 330 core
// Lit mesh: Lambert (two-sided) plus ambient, times the material diffuse colour; or a flat
// colour when u_flatColour.a > 0 (wireframe overlay).
in vec3 v_normal;
in vec3 v_diffuse;
uniform vec3 u_lightDirection;  // world frame, towards the light, unit length
uniform float u_ambient;
uniform vec4 u_flatColour;
out vec4 o_colour;
void main() {
  if (u_flatColour.a > 0.0) {
    o_colour = vec4(u_flatColour.rgb, 1.0);
    return;
  }
  float lambert = abs(dot(normalize(v_normal), u_lightDirection));
  o_colour = vec4(v_diffuse * (u_ambient + (1.0 - u_ambient) * lambert), 1.0);
}
