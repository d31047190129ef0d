// copy_background.frag.glsl - copies the background pass (colour and depth)
// into the target framebuffer (whatever its depth format).
in vec2 v_uv;

uniform sampler2D u_background;
uniform sampler2D u_background_depth;

out vec4 o_color;

void main() {
  o_color = texture(u_background, v_uv);
  gl_FragDepth = texture(u_background_depth, v_uv).r;
}
