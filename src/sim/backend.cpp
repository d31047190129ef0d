#include "sim/backend.h"

#include "core/error.h"

namespace ff {

const char* phaseName(Phase p) {
  static const char* names[] = {"grid",     "density",   "forces",         "control_scale", "control_forces",
                                "pressure", "integrate", "shape_matching", "metrics"};
  int i = int(p);
  return i >= 0 && i < int(Phase::Count) ? names[i] : "?";
}

void Backend::saveState(StateWriter&) const {
  throw Error("the " + name() + " backend cannot write checkpoints; run with --backend cpu");
}

void Backend::loadState(StateReader&) {
  throw Error("the " + name() + " backend cannot resume from a checkpoint; run with --backend cpu");
}

}  // namespace ff
