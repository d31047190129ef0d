// lines.geom.glsl - turns each segment into a screen-aligned quad u_width
// pixels wide (core profile lines are one pixel wide), after clipping it to
// the part in front of the eye.
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

uniform vec2 u_viewport;  // pixels
uniform float u_width;    // pixels

void main() {
  vec4 a = gl_in[0].gl_Position, b = gl_in[1].gl_Position;
  const float kMinW = 1e-4;
  if (a.w < kMinW && b.w < kMinW) return;
  if (a.w < kMinW) a = mix(a, b, (kMinW - a.w) / (b.w - a.w));
  if (b.w < kMinW) b = mix(b, a, (kMinW - b.w) / (a.w - b.w));
  vec2 sa = a.xy / a.w * u_viewport, sb = b.xy / b.w * u_viewport;
  vec2 d = sb - sa;
  float len = length(d);
  vec2 dir = len > 1e-6 ? d / len : vec2(1.0, 0.0);
  vec2 offset = vec2(-dir.y, dir.x) * u_width / u_viewport;  // ndc units (half width * 2 / viewport)
  gl_Position = vec4(a.xy + offset * a.w, a.zw);
  EmitVertex();
  gl_Position = vec4(a.xy - offset * a.w, a.zw);
  EmitVertex();
  gl_Position = vec4(b.xy + offset * b.w, b.zw);
  EmitVertex();
  gl_Position = vec4(b.xy - offset * b.w, b.zw);
  EmitVertex();
  EndPrimitive();
}
