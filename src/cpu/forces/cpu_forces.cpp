// cpu_forces.cpp - the one place that registers the OpenMP backend's
// non-pressure forces: a new force is its file in src/cpu/forces/ (a
// CpuForce and its make function) and one line in each list below.
#include "cpu/forces/cpu_forces.h"

namespace ff {

std::unique_ptr<CpuForce> makeCpuGravity();    // gravity.cpp
std::unique_ptr<CpuForce> makeCpuViscosity();  // viscosity.cpp
std::unique_ptr<CpuForce> makeCpuControl();    // control.cpp

std::vector<std::unique_ptr<CpuForce>> makeCpuForces() {
  std::vector<std::unique_ptr<CpuForce>> forces;
  forces.push_back(makeCpuGravity());
  forces.push_back(makeCpuViscosity());
  forces.push_back(makeCpuControl());
  return forces;
}

}  // namespace ff
