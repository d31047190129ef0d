#include "cpu/pressure_solver.h"

#include "core/error.h"
#include "cpu/dfsph_solver.h"

namespace ff {

std::unique_ptr<PressureSolver> makeCpuPressureSolver(PressureSolverKind kind) {
  switch (kind) {
    case PressureSolverKind::Wcsph:
      return std::make_unique<WcsphSolver>();
    case PressureSolverKind::Dfsph:
      return std::make_unique<DfsphSolver>();
  }
  throw Error(std::string("params.fluid.solver: no OpenMP implementation of \"") + solverName(kind) + "\"");
}

}  // namespace ff
