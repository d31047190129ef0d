// frame_exporter.h - writes a run's frames into a folder at a frame rate:
// per frame, for each chosen format, the fluid and the control particles in
// files of their own, numbered by frame (fluid_00000.vtu, control_00000.bgeo,
// ...), each carrying its simulated time; with vtk also the indexes
// fluid.pvd and control.pvd. Used by `flowform run`, `flowform render`, the
// viewer's recording and the Python module; src/sim/export_frame.h feeds it
// from a Simulation.
//
// Attributes per format (positions y-up, metres, SI units):
//   vtk  fluid:   velocity(3) id density pressure
//        control: velocity(3) id rest_position(3) s
//   bgeo fluid:   P v(3) id(int) density pressure; detail attribute time
//        control: P v(3) id(int) rest(3) s;        detail attribute time
//   ply  fluid:   x y z vx vy vz id(int32)
//        control: x y z x0 y0 z0 s                 ("comment time T" in both)
// With options.surface.enabled also surface_NNNNN.obj or .ply, the liquid's
// closed surface (surface/particle_surface.h), and with surface.vdb its
// level set surface_NNNNN.vdb.
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "io/export_options.h"
#include "io/particle_frame.h"
#include "io/pvd_index.h"

namespace ff {

class FrameExporter {
 public:
  // Checks the options and prepares the folder (io/export_folder.h: another
  // run's frames are refused unless overwrite). Throws ff::Error.
  explicit FrameExporter(ExportOptions options);

  // Whether the next frame falls due at this time and step: the first
  // always, then frame k when k / fps seconds have passed since the first (or
  // every_steps steps after the previous one). At most one frame per step.
  bool due(double time, long step) const;
  // Writes `frame` as the next frame (frame numbers count up from 0).
  void write(const ParticleFrame& frame);
  // The frame buffer a producer may fill before calling write (reused).
  ParticleFrame& buffer() { return frame_; }

  long frames() const { return frames_; }
  // Wall milliseconds per frame spent on each part so far, e.g.
  // "vtk 2.1, bgeo 1.0, surface 310.4 ms per frame" (empty before the first frame).
  std::string costReport() const;
  const ExportOptions& options() const { return options_; }
  // The path of a frame file: DIR/PREFIX_NNNNN.EXT.
  std::string framePath(const char* prefix, long frame, const char* ext) const;

 private:
  ExportOptions options_;
  long frames_ = 0;
  double start_time_ = 0.0;
  long last_step_ = 0;
  ParticleFrame frame_;
  std::vector<std::pair<std::string, double>> ms_;  // part -> total milliseconds
  std::unique_ptr<PvdIndex> fluid_pvd_, control_pvd_;
};

}  // namespace ff
