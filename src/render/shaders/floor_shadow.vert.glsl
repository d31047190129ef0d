// floor_shadow.vert.glsl - each particle projected along the light onto the
// floor plane, as a square in the floor's shadow map (x, z over u_rect).
layout(location = 0) in vec3 a_center;  // world, per instance

uniform vec3 u_light_world;  // unit, towards the light (y > 0)
uniform float u_floor_y;
uniform vec4 u_rect;    // xz min, xz max of the map
uniform float u_radius;  // splat radius, metres

out vec2 v_local;  // -1 .. 1 across the splat

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
  float height = max(a_center.y - u_floor_y, 0.0);
  vec2 ground = a_center.xz - height * u_light_world.xz / max(u_light_world.y, 0.1);
  vec2 p = ground + corner * u_radius;
  vec2 ndc = 2.0 * (p - u_rect.xy) / (u_rect.zw - u_rect.xy) - 1.0;
  v_local = corner;
  gl_Position = vec4(ndc, 0.0, 1.0);
}
