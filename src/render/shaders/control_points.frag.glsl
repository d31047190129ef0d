// control_points.frag.glsl - control particles as small spheres coloured by
// their density scale s_i (eq. 5): s = 0 (surrounded by liquid, the target is
// filled there) green, s = 1 (no liquid around, still to be filled) red, as
// in the paper's Fig. 11; yellow halfway.
in vec3 v_ray;
flat in vec3 v_center;
flat in float v_value;

uniform mat4 u_proj;
uniform float u_radius;
uniform vec3 u_light_eye;

out vec4 o_color;

vec3 coverageColor(float s) {
  const vec3 covered = vec3(0.10, 0.80, 0.25);
  const vec3 half_covered = vec3(0.95, 0.85, 0.10);
  const vec3 empty = vec3(0.90, 0.12, 0.10);
  s = clamp(s, 0.0, 1.0);
  return s < 0.5 ? mix(covered, half_covered, 2.0 * s) : mix(half_covered, empty, 2.0 * s - 1.0);
}

void main() {
  vec3 p, n;
  float chord;
  if (!sphereHit(v_ray, v_center, u_radius, p, n, chord)) discard;
  float diffuse = max(dot(n, u_light_eye), 0.0);
  o_color = vec4(coverageColor(v_value) * (0.45 + 0.55 * diffuse), 1.0);
  gl_FragDepth = windowDepth(u_proj, p);
}
