#include "control/shape_match_args.h"

#include <limits>

#include "ff_anchor.h"

namespace ff {

FfShapeMatchArgs shapeMatchArgs(const ShapeMatchParams& sm, float feedback, uint32_t n, uint32_t nclusters,
                                float w, const float gravity[3], const float* lo, const float* hi, int tag) {
  FfShapeMatchArgs a{};
  const float inf = std::numeric_limits<float>::infinity();
  for (int d = 0; d < 3; ++d) a.box_lo[d] = lo ? lo[d] : -inf, a.box_hi[d] = hi ? hi[d] : inf;
  a.w = w;
  a.h = sm.time_step, a.alpha = sm.stiffness;
  a.feedback = feedback, a.damping = sm.damping;
  a.n = n, a.nclusters = nclusters;
  a.iterations = sm.rotation_iterations;
  ff_float3 up;
  a.anchor = sm.anchor != 0 && ff_anchor_up(gravity, &up) ? sm.anchor : 0;
  a.g = ff_anchor_g(gravity);
  a.tag = tag;
  return a;
}

}  // namespace ff
