// fluid_depth.frag.glsl - sphere depth splats: each fragment of a particle's
// square writes the eye depth of the sphere's front surface (and the matching
// window depth, so the nearest sphere wins the depth test).
in vec3 v_ray;
flat in vec3 v_center;
flat in float v_value;

uniform mat4 u_proj;
uniform float u_radius;

out vec2 o_depth;  // eye depth, coverage

void main() {
  vec3 p, n;
  float chord;
  if (!sphereHit(v_ray, v_center, u_radius, p, n, chord)) discard;
  o_depth = vec2(-p.z, 1.0);
  gl_FragDepth = windowDepth(u_proj, p);
}
