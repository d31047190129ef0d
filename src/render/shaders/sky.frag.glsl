// sky.frag.glsl - the backdrop: the sky gradient along each pixel's view ray.
in vec2 v_uv;

uniform mat4 u_proj;
uniform mat3 u_eye_to_world;

out vec4 o_color;

void main() {
  vec3 ray = eyeFromDepth(u_proj, v_uv, 1.0);
  o_color = vec4(skyColor(normalize(u_eye_to_world * ray)), 1.0);
}
