// export_frame.h - feeds a FrameExporter (src/io/frame_exporter.h) from a
// Simulation: the one place that reads a run's state back for export, used
// by `flowform run`, `flowform render`, the viewer's recording and the Python
// module.
#pragma once
#include "io/frame_exporter.h"
#include "io/particle_frame.h"
#include "sim/simulation.h"

namespace ff {

// Copies the simulation's current state (from the device, for OpenCL).
void readParticleFrame(Simulation& sim, ParticleFrame& out);

// Writes the next frame if one is due at the simulation's time and step
// (FrameExporter::due). Returns whether it wrote. Throws ff::Error.
bool exportFrameIfDue(Simulation& sim, FrameExporter& exporter);
// Writes the next frame now (e.g. one per rendered frame).
void exportFrameNow(Simulation& sim, FrameExporter& exporter);

}  // namespace ff
