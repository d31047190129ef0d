// particles.frag.glsl - plain particle mode: each particle a lit sphere in
// the liquid's colour, with a Fresnel sky reflection and a highlight.
in vec3 v_ray;
flat in vec3 v_center;
flat in float v_value;

uniform mat4 u_proj;
uniform mat3 u_eye_to_world;
uniform float u_radius;
uniform vec3 u_color;
uniform vec3 u_light_eye;

out vec4 o_color;

void main() {
  vec3 p, n;
  float chord;
  if (!sphereHit(v_ray, v_center, u_radius, p, n, chord)) discard;
  vec3 v = normalize(-p);
  float diffuse = max(dot(n, u_light_eye), 0.0);
  vec3 base = u_color * (0.35 + 0.65 * diffuse);
  float fresnel = 0.04 + 0.96 * pow(1.0 - clamp(dot(n, v), 0.0, 1.0), 5.0);
  vec3 reflected = skyColor(normalize(u_eye_to_world * reflect(-v, n)));
  float specular = pow(max(dot(n, normalize(u_light_eye + v)), 0.0), 80.0) * 0.6;
  o_color = vec4(mix(base, reflected, fresnel) + vec3(specular), 1.0);
  gl_FragDepth = windowDepth(u_proj, p);
}
