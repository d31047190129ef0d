// export_frame.cpp - a Simulation's state into a ParticleFrame.
#include "sim/export_frame.h"

#include <cmath>

namespace ff {

void readParticleFrame(Simulation& sim, ParticleFrame& out) {
  out.time = sim.time();
  out.step = sim.stepCount();
  out.spacing = sim.scene().params.fluid.restSpacing();
  Backend& b = sim.backend();
  b.readFluid(out.fluid);
  b.readDensity(out.density, out.pressure);
  ControlSet set;
  ControlFields fields;
  b.readControl(set, fields);
  FluidState& c = out.control;
  c.x = std::move(set.x), c.y = std::move(set.y), c.z = std::move(set.z);
  c.vx = std::move(set.vx), c.vy = std::move(set.vy), c.vz = std::move(set.vz);
  c.id.resize(c.x.size());
  for (size_t i = 0; i < c.id.size(); ++i) c.id[i] = uint32_t(i);
  out.rest_x = std::move(set.x0), out.rest_y = std::move(set.y0), out.rest_z = std::move(set.z0);
  out.s = std::move(fields.s);
}

bool exportFrameIfDue(Simulation& sim, FrameExporter& exporter) {
  if (!exporter.due(sim.time(), sim.stepCount())) return false;
  exportFrameNow(sim, exporter);
  return true;
}

void exportFrameNow(Simulation& sim, FrameExporter& exporter) {
  readParticleFrame(sim, exporter.buffer());
  exporter.write(exporter.buffer());
}

}  // namespace ff
