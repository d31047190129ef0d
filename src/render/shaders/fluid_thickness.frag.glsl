// fluid_thickness.frag.glsl - thickness splats, blended additively: the
// chord of the view ray through each sphere, summed over the particles and
// scaled by particle volume / sphere volume (the spheres overlap), which
// gives about the metres of liquid along the ray.
in vec3 v_ray;
flat in vec3 v_center;
flat in float v_value;

uniform float u_radius;
uniform float u_scale;

out float o_thickness;

void main() {
  vec3 p, n;
  float chord;
  if (!sphereHit(v_ray, v_center, u_radius, p, n, chord)) discard;
  o_thickness = chord * u_scale;
}
