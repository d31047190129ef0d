// ghost.vert.glsl - one face of a target voxel per instance (a triangle
// strip of 4 vertices), rotated with the best rigid fit of the control
// particles.
layout(location = 0) in vec4 a_face;  // xyz: voxel centre (world), w: face 0..5 = -x +x -y +y -z +z

uniform mat4 u_view;
uniform mat4 u_proj;
uniform mat3 u_rotation;  // shape frame -> world
uniform float u_voxel;
uniform vec3 u_eye_world;

out vec3 v_normal;     // world
out float v_facing;    // > 0 where the face looks towards the eye

void main() {
  int face = int(a_face.w + 0.5);
  int axis = face / 2;
  vec3 n = vec3(0.0), u = vec3(0.0), v = vec3(0.0);
  n[axis] = (face % 2 == 1) ? 1.0 : -1.0;
  u[(axis + 1) % 3] = 1.0;
  v[(axis + 2) % 3] = 1.0;
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) - 0.5;
  vec3 local = 0.5 * n + corner.x * u + corner.y * v;
  vec3 world = a_face.xyz + u_rotation * (local * u_voxel);
  v_normal = u_rotation * n;
  v_facing = dot(v_normal, u_eye_world - world);
  gl_Position = u_proj * u_view * vec4(world, 1.0);
}
