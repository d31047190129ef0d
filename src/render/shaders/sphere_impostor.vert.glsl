// sphere_impostor.vert.glsl - one camera-facing square per particle
// (instanced triangle strip of 4 vertices), large enough to hold the
// sphere's perspective silhouette; the fragment shaders intersect the view
// ray with the sphere. Unlike GL points these have no size limit and are not
// dropped when their centre leaves the screen.
layout(location = 0) in vec3 a_center;  // world space, per instance
layout(location = 1) in float a_value;  // per instance (control particles: s_i)

uniform mat4 u_view;
uniform mat4 u_proj;
uniform float u_radius;

out vec3 v_ray;           // eye-space point on the square: the view ray's direction
flat out vec3 v_center;   // eye-space sphere centre
flat out float v_value;

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
  vec3 c = (u_view * vec4(a_center, 1.0)).xyz;
  float d = length(c);
  float r = u_radius;
  // The tangent cone from the eye cuts the plane through the centre in a
  // circle of radius r d / sqrt(d^2 - r^2) (on the axis), stretched by up to
  // 1 / cos(angle off the axis) radially; the square covers both.
  float cone = d > 1.05 * r ? d / sqrt(d * d - r * r) : 3.3;
  float off_axis = max(-c.z / max(d, 1e-6), 0.25);
  float half_size = r * cone / off_axis;
  vec3 p = c + vec3(corner * half_size, 0.0);
  v_ray = p;
  v_center = c;
  v_value = a_value;
  gl_Position = u_proj * vec4(p, 1.0);
}
