// world.vert.glsl - world-space triangles with a normal (floor, walls).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_view;
uniform mat4 u_proj;

out vec3 v_world;
out vec3 v_normal;

void main() {
  v_world = a_position;
  v_normal = a_normal;
  gl_Position = u_proj * u_view * vec4(a_position, 1.0);
}
