// common.glsl - helpers shared by several shaders: the sky (the backdrop and
// what the liquid reflects), eye-space reconstruction and depth conversion.

const vec3 kSkyZenith = vec3(0.30, 0.50, 0.80);
const vec3 kSkyHorizon = vec3(0.85, 0.90, 0.96);
const vec3 kGround = vec3(0.62, 0.63, 0.66);

// Radiance seen along world direction `d` (unit): a vertical gradient above
// the horizon, a grey ground below it (the floor, seen in reflections).
vec3 skyColor(vec3 d) {
  if (d.y >= 0.0) return mix(kSkyHorizon, kSkyZenith, pow(d.y, 0.5));
  return mix(kSkyHorizon, kGround, 1.0 - exp(-4.0 * -d.y));
}

// Eye-space point on the view ray through texture coordinate `uv` at eye
// depth `z` (> 0, metres in front of the eye), for a symmetric perspective
// projection `proj`.
vec3 eyeFromDepth(mat4 proj, vec2 uv, float z) {
  vec2 ndc = 2.0 * uv - 1.0;
  return vec3(ndc.x * z / proj[0][0], ndc.y * z / proj[1][1], -z);
}

// Window depth (0 near .. 1 far) of an eye-space point.
float windowDepth(mat4 proj, vec3 p) {
  vec4 clip = proj * vec4(p, 1.0);
  return 0.5 * clip.z / clip.w + 0.5;
}
