// smooth_depth.frag.glsl - one separable pass (along u_step) of a bilateral
// filter on the liquid's eye depth (after Green 2010), in the red channel.
// The passes run along the rows and columns, or along the diagonals.
//
// The spatial Gaussian's sigma is the particle's projected radius times
// u_scale, so the surface is smoothed over the same world-space extent near
// and far. The range term keeps separate sheets of liquid (a depth jump)
// apart; it measures a sample against the plane through the centre pixel
// (its slope from the nearer neighbour difference), not against the centre's
// depth, so sloped surfaces (a floor seen at an angle) are smoothed as well
// as facing ones. And instead of the weighted mean, the pass takes the
// weighted least-squares line through the samples at the centre: where
// samples are missing on one side (a silhouette, a hole in a thin sheet) the
// mean of a sloped surface would be pulled to one side and leave streaks,
// the line is not. Pixels without liquid (depth 0) give no depth and receive
// it only inside narrow gaps, so the silhouette does not grow or shrink.
//
// The green channel carries the liquid's "coverage": 1 where the splats put
// liquid, blurred with the same spatial Gaussian, with empty pixels and
// pixels across a depth jump counting as 0. It falls from 1 inside to about
// 0.5 at a silhouette, where the composite rounds the surface off.
in vec2 v_uv;

uniform sampler2D u_depth;     // r: eye depth (0 = none), g: coverage
uniform vec2 u_step;           // one tap along the filter direction, in uv
uniform float u_step_pixels;   // length of that tap in pixels (1 along rows, sqrt 2 along diagonals)
uniform float u_radius_px_1m;  // projected particle radius in pixels at 1 m eye depth
uniform float u_scale;         // sigma in particle radii
uniform float u_range;         // depth difference (m) at which a sample's weight falls to 1/e
uniform int u_max_half_width;  // taps on each side at most
uniform int u_gap_taps;        // widest gap closed on each side of a pixel, in taps

out vec2 o_depth;

// The first liquid sample within `taps` taps along `dir` (+1 or -1): its
// depth, and its distance in taps (0 when there is none).
vec2 nearestLiquid(float dir, int taps) {
  for (int i = 1; i <= taps; ++i) {
    float s = texture(u_depth, v_uv + dir * float(i) * u_step).r;
    if (s > 0.0) return vec2(s, float(i));
  }
  return vec2(0.0);
}

void main() {
  float z = texture(u_depth, v_uv).r;
  float slope = 0.0;  // depth change per tap
  float radius_taps = u_radius_px_1m / u_step_pixels;  // at 1 m
  if (z <= 0.0) {
    // A gap no wider than about a particle's diameter between liquid on both
    // sides (a hole in a thin sheet, between two particles) is closed with
    // the line between its sides; outside a silhouette there is liquid on one
    // side only, so the silhouette does not grow.
    vec2 before = nearestLiquid(-1.0, u_gap_taps);
    vec2 after = before.y > 0.0 ? nearestLiquid(1.0, u_gap_taps) : vec2(0.0);
    float gap = before.y + after.y;
    if (before.y == 0.0 || after.y == 0.0 || gap > 2.0 * radius_taps / min(before.x, after.x)) {
      o_depth = vec2(0.0);
      return;
    }
    slope = (after.x - before.x) / gap;
    z = before.x + slope * before.y;
  } else {
    // The smaller one-sided difference (a depth jump on one side does not
    // count), limited to the range.
    float zp = texture(u_depth, v_uv + u_step).r, zm = texture(u_depth, v_uv - u_step).r;
    if (zp > 0.0 && zm > 0.0)
      slope = abs(zp - z) < abs(z - zm) ? zp - z : z - zm;
    else if (zp > 0.0)
      slope = zp - z;
    else if (zm > 0.0)
      slope = z - zm;
  }
  slope = clamp(slope, -0.5 * u_range, 0.5 * u_range);

  float sigma = max(u_scale * u_radius_px_1m / z, 0.5) / u_step_pixels;  // in taps
  int half_width = min(int(ceil(2.0 * sigma)), u_max_half_width);
  float inv_two_sigma2 = 1.0 / (2.0 * sigma * sigma);
  float inv_range2 = 1.0 / (u_range * u_range);
  // Weighted sums for the line d(i) = a + b i through the samples' depths
  // relative to the centre, d = s - z (small numbers: no cancellation).
  float w0 = 0.0, wi = 0.0, wii = 0.0, wd = 0.0, wid = 0.0;
  float coverage = 0.0, spatial_weight = 0.0;
  float lo = 0.0, hi = 0.0;  // range of the samples that count (the centre's d = 0 among them)
  for (int k = -half_width; k <= half_width; ++k) {
    float i = float(k);
    vec2 s = texture(u_depth, v_uv + i * u_step).rg;
    float ws = exp(-i * i * inv_two_sigma2);
    spatial_weight += ws;
    if (s.r <= 0.0) continue;
    float d = s.r - z;
    float off_plane = d - slope * i;
    float w = ws * exp(-off_plane * off_plane * inv_range2);
    w0 += w;
    wi += w * i;
    wii += w * i * i;
    wd += w * d;
    wid += w * i * d;
    if (w > 0.05 * ws) {
      lo = min(lo, d);
      hi = max(hi, d);
    }
    coverage += s.g * w;
  }
  float det = w0 * wii - wi * wi;
  float a = det > 1e-4 * w0 * w0 ? (wd * wii - wi * wid) / det : wd / w0;
  // The line's value never leaves the samples' range (no overshoot where few
  // samples on one side make the line steep).
  o_depth = vec2(z + clamp(a, lo, hi), coverage / spatial_weight);
}
