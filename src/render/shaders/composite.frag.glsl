// composite.frag.glsl - shades the smoothed liquid surface over the
// background: normals from the depth buffer, Fresnel (Schlick) between the
// refracted background (offset by the normal and the thickness, tinted by
// Beer-Lambert absorption) and the reflected sky, plus a specular highlight.
// Writes the liquid's depth, or the background's where that is nearer (the
// container's front edges), so later overlays are depth-tested against both.
in vec2 v_uv;

uniform sampler2D u_background;  // RGBA8
uniform sampler2D u_background_depth;
uniform sampler2D u_fluid_depth;  // r: smoothed eye depth (0 = no liquid), g: coverage
uniform sampler2D u_thickness;    // summed chord lengths, metres

uniform mat4 u_proj;
uniform mat3 u_eye_to_world;  // rotation part of the inverse view matrix
uniform vec2 u_texel;         // 1 / viewport size
uniform vec3 u_fluid_color;
uniform float u_absorption;     // 1/m
uniform vec3 u_light_eye;       // unit vector towards the light, eye space
uniform float u_refraction;     // uv offset per metre of thickness, per unit of normal tilt
uniform float u_max_thickness;  // thickness beyond which the refraction offset stops growing
uniform float u_min_thickness;  // the thinnest liquid (about a particle's volume over its cross-section)
uniform float u_occlusion_slack;  // metres the liquid may dip behind the background and still show

out vec4 o_color;

vec3 positionAt(vec2 uv, out bool ok) {
  float z = texture(u_fluid_depth, uv).r;
  ok = z > 0.0;
  return eyeFromDepth(u_proj, uv, max(z, 1e-6));
}

// Normal from the depth buffer: of the two one-sided differences along each
// axis, the smaller in depth, so that silhouettes (a depth jump on one side)
// do not tilt the normal.
vec3 normalAt(vec2 uv, vec3 p) {
  bool ok_r, ok_l, ok_u, ok_d;
  vec3 pr = positionAt(uv + vec2(u_texel.x, 0.0), ok_r);
  vec3 pl = positionAt(uv - vec2(u_texel.x, 0.0), ok_l);
  vec3 pu = positionAt(uv + vec2(0.0, u_texel.y), ok_u);
  vec3 pd = positionAt(uv - vec2(0.0, u_texel.y), ok_d);
  vec3 dx = pr - p, dx2 = p - pl;
  if (!ok_r || (ok_l && abs(dx2.z) < abs(dx.z))) dx = dx2;
  vec3 dy = pu - p, dy2 = p - pd;
  if (!ok_u || (ok_d && abs(dy2.z) < abs(dy.z))) dy = dy2;
  if (!ok_r && !ok_l) dx = vec3(1.0, 0.0, 0.0);
  if (!ok_u && !ok_d) dy = vec3(0.0, 1.0, 0.0);
  vec3 n = cross(dx, dy);
  float len = length(n);
  return len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0);
}

// Rounds the surface off towards the silhouette: where the smoothed coverage
// falls from 1 (inside) to 0.5 (at the edge), tilt the normal outwards, down
// its gradient, up to grazing, as on a liquid edge that curves away.
vec3 roundEdge(vec2 uv, vec3 n) {
  float coverage = texture(u_fluid_depth, uv).g;
  float edge = smoothstep(0.75, 0.5, coverage);
  if (edge <= 0.0) return n;
  vec2 grad = vec2(texture(u_fluid_depth, uv + vec2(u_texel.x, 0.0)).g -
                       texture(u_fluid_depth, uv - vec2(u_texel.x, 0.0)).g,
                   texture(u_fluid_depth, uv + vec2(0.0, u_texel.y)).g -
                       texture(u_fluid_depth, uv - vec2(0.0, u_texel.y)).g);
  float len = length(grad);
  if (len < 1e-5) return n;
  float s = 0.9 * edge;                      // sine of the tilt
  float tilt = s / sqrt(1.0 - s * s);        // its tangent
  return normalize(n + vec3(-grad / len, 0.0) * tilt);
}

void main() {
  vec4 background = texture(u_background, v_uv);
  float background_depth = texture(u_background_depth, v_uv).r;
  float z = texture(u_fluid_depth, v_uv).r;
  vec3 p = eyeFromDepth(u_proj, v_uv, max(z, 1e-6));
  float depth = windowDepth(u_proj, p);
  // Eye depth of the background from its window depth (inverting the
  // perspective projection). The liquid shows unless it lies behind the
  // background by more than the slack: a thin sheet on the floor has its
  // splats' sides dip a little under the floor plane, which must not punch
  // holes into it, while the container's front edges still hide the liquid.
  float background_z = u_proj[3][2] / (2.0 * background_depth - 1.0 + u_proj[2][2]);
  if (z <= 0.0 || (depth >= background_depth && z > background_z + u_occlusion_slack)) {
    o_color = background;
    gl_FragDepth = background_depth;
    return;
  }
  vec3 n = roundEdge(v_uv, normalAt(v_uv, p));
  vec3 v = normalize(-p);
  // The splats' chords fall to zero at their rims; a real liquid edge is a
  // rounded surface at least about a particle thick, so the silhouette stays crisp.
  float thickness = max(texture(u_thickness, v_uv).r, u_min_thickness);

  // Refraction: the background behind, displaced along the normal's screen
  // projection, more through thicker liquid; then Beer-Lambert absorption
  // (the complement of the liquid's colour is absorbed) and the light the
  // liquid scatters back in its own colour, lit from the light's side.
  vec2 offset = n.xy * u_refraction * (0.01 + min(thickness, u_max_thickness));
  vec3 behind = texture(u_background, clamp(v_uv + offset, vec2(0.0), vec2(1.0))).rgb;
  vec3 transmittance = exp(-u_absorption * thickness * (vec3(1.0) - u_fluid_color));
  float in_scatter = 1.0 - exp(-u_absorption * thickness * 0.35);
  float lit = 0.5 + 0.5 * dot(n, u_light_eye);  // wrapped diffuse: shows the shape
  vec3 refracted = behind * transmittance + u_fluid_color * in_scatter * (0.2 + 0.6 * lit * lit);

  vec3 r = u_eye_to_world * reflect(-v, n);
  vec3 reflected = skyColor(normalize(r));
  float cos_v = clamp(dot(n, v), 0.0, 1.0);
  float fresnel = 0.02 + 0.98 * pow(1.0 - cos_v, 5.0);

  vec3 h = normalize(u_light_eye + v);
  float n_h = max(dot(n, h), 0.0);
  vec3 specular = vec3(1.0, 0.98, 0.94) * (pow(n_h, 600.0) * 2.5 + pow(n_h, 40.0) * 0.25);

  vec3 color = mix(refracted, reflected, fresnel) + specular;
  o_color = vec4(color, 1.0);
  gl_FragDepth = min(depth, background_depth);
}
