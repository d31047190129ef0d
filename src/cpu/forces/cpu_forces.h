// cpu_forces.h - the OpenMP backend's registered non-pressure forces.
#pragma once
#include <memory>
#include <vector>

#include "cpu/forces/cpu_force.h"

namespace ff {

// Gravity, viscosity, control: every force the backend runs, in order.
std::vector<std::unique_ptr<CpuForce>> makeCpuForces();

}  // namespace ff
