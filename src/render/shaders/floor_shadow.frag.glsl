// floor_shadow.frag.glsl - summed, softened chord lengths (blended
// additively): how much liquid the light crosses before the floor.
in vec2 v_local;

uniform float u_radius;

out float o_thickness;

void main() {
  float d2 = dot(v_local, v_local);
  if (d2 >= 1.0) discard;
  o_thickness = 2.0 * u_radius * sqrt(1.0 - d2) * (1.0 - d2);
}
