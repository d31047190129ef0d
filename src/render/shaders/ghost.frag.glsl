// ghost.frag.glsl - the target's surface voxels as a translucent shell (only
// the faces towards the eye, so it reads as one layer).
in vec3 v_normal;
in float v_facing;

uniform vec3 u_light_world;
uniform vec4 u_color;

out vec4 o_color;

void main() {
  if (v_facing <= 0.0) discard;
  float diffuse = abs(dot(normalize(v_normal), u_light_world));
  o_color = vec4(u_color.rgb * (0.55 + 0.45 * diffuse), u_color.a);
}
