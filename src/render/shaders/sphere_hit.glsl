// sphere_hit.glsl - the view ray (from the eye, through eye-space point
// `ray`) against the sphere (centre c, radius r). On a hit gives the front
// surface point p, the unit normal there and the chord length through the
// sphere along the ray.
bool sphereHit(vec3 ray, vec3 c, float r, out vec3 p, out vec3 n, out float chord) {
  vec3 d = normalize(ray);
  float b = dot(d, c);            // distance along the ray to the closest approach
  vec3 closest = c - b * d;
  float h2 = r * r - dot(closest, closest);
  if (h2 < 0.0 || b <= 0.0) return false;
  float h = sqrt(h2);
  p = d * (b - h);
  n = (p - c) / r;
  chord = 2.0 * h;
  return true;
}
