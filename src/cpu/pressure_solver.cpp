#include "cpu/pressure_solver.h"

#include "core/error.h"

namespace ff {

std::unique_ptr<PressureSolver> makeCpuPressureSolver(PressureSolverKind kind) {
  switch (kind) {
    case PressureSolverKind::Wcsph:
      return std::make_unique<WcsphSolver>();
  }
  throw Error(std::string("params.fluid.solver: no OpenMP implementation of \"") + solverName(kind) + "\"");
}

}  // namespace ff
