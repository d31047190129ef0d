#include "control/shape_match_args.h"

#include <limits>

namespace ff {

FfShapeMatchArgs shapeMatchArgs(const ShapeMatchParams& sm, float feedback, uint32_t n, uint32_t nclusters,
                                float w, bool anchored, const float* lo, const float* hi, int tag) {
  FfShapeMatchArgs a{};
  const float inf = std::numeric_limits<float>::infinity();
  for (int d = 0; d < 3; ++d) a.box_lo[d] = lo ? lo[d] : -inf, a.box_hi[d] = hi ? hi[d] : inf;
  a.w = w;
  a.h = sm.time_step, a.alpha = sm.stiffness;
  a.feedback = feedback, a.damping = sm.damping;
  a.n = n, a.nclusters = nclusters;
  a.iterations = sm.rotation_iterations;
  a.anchored = anchored ? 1 : 0;
  a.tag = tag;
  return a;
}

}  // namespace ff
