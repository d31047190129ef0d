// walls.frag.glsl - the container's far walls as faintly tinted glass (the
// near walls are left out so they do not veil the liquid; their edges are
// drawn as lines).
in vec3 v_world;
in vec3 v_normal;  // outward

uniform vec3 u_eye_world;
uniform vec4 u_color;  // rgb, alpha

out vec4 o_color;

void main() {
  vec3 to_eye = u_eye_world - v_world;
  if (dot(v_normal, to_eye) > 0.0) discard;  // a near wall
  float grazing = 1.0 - abs(dot(normalize(v_normal), normalize(to_eye)));
  o_color = vec4(u_color.rgb, u_color.a * (0.6 + 0.8 * grazing));
}
