#version 330 core
// Lit mesh (OBJ models): model -> world transform, normals to world by the normal matrix. With
// u_distort each vertex lands where OpenCV's lens model (k1 k2 p1 p2 k3 k4 k5 k6, as
// cv::projectPoints) puts it; the depth stays that of the pinhole projection. Edges between
// vertices stay straight, so large faces bend only at their vertices.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_diffuse;
uniform mat4 u_viewProjection;
uniform mat4 u_model;
uniform mat3 u_normalMatrix;
uniform int u_distort;
uniform mat4 u_worldToCamera;    // OpenCV axes
uniform vec4 u_focalCentre;      // fx, fy, cx, cy
uniform float u_skew;
uniform vec2 u_imageSize;
uniform vec4 u_distortionA;      // k1, k2, p1, p2
uniform vec4 u_distortionB;      // k3, k4, k5, k6
out vec3 v_normal;
out vec3 v_diffuse;
void main() {
  v_normal = u_normalMatrix * a_normal;
  v_diffuse = a_diffuse;
  vec4 world = u_model * vec4(a_position, 1.0);
  gl_Position = u_viewProjection * world;
  if (u_distort != 0) {
    vec3 X = (u_worldToCamera * world).xyz;
    if (X.z > 0.0) {
      vec2 n = X.xy / X.z;
      float r2 = dot(n, n), r4 = r2 * r2, r6 = r4 * r2;
      float radial = (1.0 + u_distortionA.x * r2 + u_distortionA.y * r4 + u_distortionB.x * r6) /
                     (1.0 + u_distortionB.y * r2 + u_distortionB.z * r4 + u_distortionB.w * r6);
      float p1 = u_distortionA.z, p2 = u_distortionA.w;
      vec2 d = n * radial + vec2(2.0 * p1 * n.x * n.y + p2 * (r2 + 2.0 * n.x * n.x),
                                 p1 * (r2 + 2.0 * n.y * n.y) + 2.0 * p2 * n.x * n.y);
      vec2 pixel = vec2(u_focalCentre.x * d.x + u_skew * d.y + u_focalCentre.z,
                        u_focalCentre.y * d.y + u_focalCentre.w);
      vec2 ndc = vec2(2.0 * (pixel.x + 0.5) / u_imageSize.x - 1.0,
                      1.0 - 2.0 * (pixel.y + 0.5) / u_imageSize.y);
      gl_Position.xy = ndc * gl_Position.w;
    }
  }
}
