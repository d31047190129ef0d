// floor.frag.glsl - a lit checkerboard floor, anti-aliased by box-filtering
// the checker over the pixel's footprint, darkened under the liquid (a soft
// shadow from a top-down thickness map) and fading into the horizon far away.
in vec3 v_world;
in vec3 v_normal;

uniform float u_tile;           // checker square edge, metres
uniform vec3 u_center;          // the container's centre on the floor
uniform float u_fade_distance;  // the floor is gone into the horizon at this distance from u_center
uniform vec3 u_eye_world;
uniform vec3 u_light_world;  // unit vector towards the light
uniform sampler2D u_shadow;  // thickness seen from above over the shadow rectangle
uniform vec4 u_shadow_rect;  // xz min, xz max of u_shadow
uniform float u_shadow_strength;

out vec4 o_color;

// Mean over [x - w/2, x + w/2] of the square wave that is +1 on [0, 1) and -1
// on [1, 2) (period 2), from its integral F(x) = 1 - |mod(x, 2) - 1|.
float filteredSquare(float x, float w) {
  float a = x - 0.5 * w, b = x + 0.5 * w;
  float fa = 1.0 - abs(mod(a, 2.0) - 1.0), fb = 1.0 - abs(mod(b, 2.0) - 1.0);
  return (fb - fa) / w;
}

void main() {
  vec2 q = v_world.xz / u_tile;
  vec2 w = max(fwidth(q), vec2(1e-4));
  float checker = filteredSquare(q.x, w.x) * filteredSquare(q.y, w.y);  // -1 .. 1
  vec3 albedo = mix(vec3(0.62, 0.63, 0.65), vec3(0.80, 0.80, 0.80), 0.5 + 0.5 * checker);
  float diffuse = max(dot(normalize(v_normal), u_light_world), 0.0);
  vec3 color = albedo * (0.45 + 0.55 * diffuse);

  vec2 s = (v_world.xz - u_shadow_rect.xy) / (u_shadow_rect.zw - u_shadow_rect.xy);
  if (all(greaterThan(s, vec2(0.0))) && all(lessThan(s, vec2(1.0)))) {
    float t = texture(u_shadow, s).r;
    color *= 1.0 - u_shadow_strength * (1.0 - exp(-t * 25.0));
  }

  float distance = length(v_world.xz - u_center.xz);
  vec3 view = normalize(v_world - u_eye_world);
  vec3 horizon = skyColor(normalize(vec3(view.x, 0.0, view.z)));
  color = mix(color, horizon, smoothstep(0.35 * u_fade_distance, u_fade_distance, distance));
  o_color = vec4(color, 1.0);
}
