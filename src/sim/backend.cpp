#include "sim/backend.h"

namespace ff {

const char* phaseName(Phase p) {
  static const char* names[] = {"grid",           "density",   "forces",         "control_scale",
                                "control_forces", "integrate", "shape_matching", "metrics"};
  int i = int(p);
  return i >= 0 && i < int(Phase::Count) ? names[i] : "?";
}

}  // namespace ff
