// metrics.h - how well the fluid matches the target, and how it behaves.
// Definitions: docs/METRICS.md.
#pragma once
#include <array>

namespace ff {

struct StepMetrics {
  long step = 0;
  double time = 0.0;
  double iou = 0.0;             // target voxels (at the control particles' best rigid fit) vs all fluid
  double coverage = 0.0;        // mean of 1 - s_i over the control particles
  double max_speed = 0.0;       // m/s
  double density_error = 0.0;   // mean |rho - rho0| / rho0
  double max_density = 0.0;     // kg/m^3 (drives the time-step control)
  int substeps = 1;             // fluid substeps taken in this step
  double kinetic_energy = 0.0;  // J
  long control_count = 0;
  // The pressure solver (0 for WCSPH, which does not iterate): iterations of
  // its solves over the step's substeps, and how many solves stopped at
  // params.fluid.max_iterations before reaching their tolerance.
  long solver_iterations = 0;
  long solver_capped = 0;
  double max_density_error = 0.0;  // max (rho - rho0) / rho0, the largest compression
  double filled = 0.0;             // share of the target's voxels that hold fluid
  double captured = 0.0;           // share of the controlled fluid inside the target
  double stray = 0.0;              // share of the controlled fluid out of every control particle's reach
  long velocity_clamps = 0;        // fluid velocities the speed limit cut since the previous metrics
  // Mean over the fluid of max(rho - rho0, 0) / rho0: the compression alone,
  // what an incompressible solver bounds (the free surface's deficit, which
  // density_error also counts, is not an error of the solve).
  double compression = 0.0;
  // How the formed shape stands at the best rigid fit (metrics/pose.h).
  double tilt = 0.0;         // degrees from upright
  double base_height = 0.0;  // m, its lowest point above the floor
  // Share of the target's thin voxels (local thickness below the control
  // radius) that hold fluid, at the best fit; 1 where it has none.
  double filled_thin = 0.0;
  // Pa, the largest fluid pressure, held over the last steps (Simulation::step;
  // drives DFSPH's substeps). Not a column.
  double max_pressure = 0.0;

  // Copies from `o` the columns that measure the fluid against the target
  // (iou, filled, captured, stray, tilt, base_height, filled_thin): those that
  // Backend::computeMetrics leaves out without `with_shape`, which
  // Simulation::step then carries over from the last step that computed them.
  // A new such column is added here.
  void copyShapeMetrics(const StepMetrics& o) {
    iou = o.iou, filled = o.filled, captured = o.captured, stray = o.stray;
    tilt = o.tilt, base_height = o.base_height, filled_thin = o.filled_thin;
  }
};

// The metrics as a table row: the columns (their names are the CSV header of
// `flowform run --metrics` and the keys of the Python module's arrays) and the
// values of one step, in the same order. New columns go at the end. A column
// that counts (an integer field) is an int in Python.
struct MetricColumn {
  const char* name;
  bool count;
};
inline constexpr std::array<MetricColumn, 21> kMetricColumns = {{{"step", true},
                                                                 {"time", false},
                                                                 {"iou", false},
                                                                 {"coverage", false},
                                                                 {"max_speed", false},
                                                                 {"density_error", false},
                                                                 {"kinetic_energy", false},
                                                                 {"control_count", true},
                                                                 {"max_density", false},
                                                                 {"substeps", true},
                                                                 {"solver_iterations", true},
                                                                 {"max_density_error", false},
                                                                 {"solver_capped", true},
                                                                 {"filled", false},
                                                                 {"captured", false},
                                                                 {"stray", false},
                                                                 {"velocity_clamps", true},
                                                                 {"compression", false},
                                                                 {"tilt", false},
                                                                 {"base_height", false},
                                                                 {"filled_thin", false}}};

inline std::array<double, kMetricColumns.size()> metricValues(const StepMetrics& m) {
  return {double(m.step),
          m.time,
          m.iou,
          m.coverage,
          m.max_speed,
          m.density_error,
          m.kinetic_energy,
          double(m.control_count),
          m.max_density,
          double(m.substeps),
          double(m.solver_iterations),
          m.max_density_error,
          double(m.solver_capped),
          m.filled,
          m.captured,
          m.stray,
          double(m.velocity_clamps),
          m.compression,
          m.tilt,
          m.base_height,
          m.filled_thin};
}

}  // namespace ff
