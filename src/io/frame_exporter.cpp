// frame_exporter.cpp - frames at a frame rate, in the chosen formats.
#include "io/frame_exporter.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "io/bgeo_writer.h"
#include "io/export_folder.h"
#include "io/ply_writer.h"
#include "io/surface_mesh_writer.h"
#include "io/vtu_writer.h"
#include "surface/particle_surface.h"

namespace ff {
namespace {

using A = PointAttribute;

const int32_t* asInt(const std::vector<uint32_t>& v) {
  return reinterpret_cast<const int32_t*>(v.data());
}

PointCloud fluidCloud(const ParticleFrame& fr, ExportFormat format) {
  const FluidState& f = fr.fluid;
  PointCloud c{f.size(), f.x.data(), f.y.data(), f.z.data(), {}, fr.time, "flowform fluid particles"};
  switch (format) {
    case ExportFormat::Vtk:
    case ExportFormat::Bgeo:
      c.attributes = {
          A::vector(format == ExportFormat::Vtk ? "velocity" : "v", f.vx.data(), f.vy.data(), f.vz.data()),
          A::integer("id", asInt(f.id)), A::scalar("density", fr.density.data()),
          A::scalar("pressure", fr.pressure.data())};
      break;
    case ExportFormat::Ply:
      c.attributes = {A::scalar("vx", f.vx.data()), A::scalar("vy", f.vy.data()),
                      A::scalar("vz", f.vz.data()), A::integer("id", asInt(f.id))};
      break;
  }
  return c;
}

PointCloud controlCloud(const ParticleFrame& fr, ExportFormat format) {
  const FluidState& s = fr.control;
  const float* sv = fr.s.data();
  const float *x0 = fr.rest_x.data(), *y0 = fr.rest_y.data(), *z0 = fr.rest_z.data();
  PointCloud c{s.size(), s.x.data(), s.y.data(), s.z.data(), {}, fr.time, "flowform control particles"};
  switch (format) {
    case ExportFormat::Vtk:
      c.attributes = {A::vector("velocity", s.vx.data(), s.vy.data(), s.vz.data()),
                      A::integer("id", asInt(s.id)), A::vector("rest_position", x0, y0, z0),
                      A::scalar("s", sv)};
      break;
    case ExportFormat::Bgeo:
      c.attributes = {A::vector("v", s.vx.data(), s.vy.data(), s.vz.data()), A::integer("id", asInt(s.id)),
                      A::vector("rest", x0, y0, z0), A::scalar("s", sv)};
      break;
    case ExportFormat::Ply:
      c.attributes = {A::scalar("x0", x0), A::scalar("y0", y0), A::scalar("z0", z0), A::scalar("s", sv)};
      break;
  }
  return c;
}

const char* extension(ExportFormat f) {
  switch (f) {
    case ExportFormat::Vtk:
      return "vtu";
    case ExportFormat::Bgeo:
      return "bgeo";
    case ExportFormat::Ply:
      return "ply";
  }
  return "";
}

void writeCloud(const std::string& path, const PointCloud& c, ExportFormat f) {
  switch (f) {
    case ExportFormat::Vtk:
      return writeVtu(path, c);
    case ExportFormat::Bgeo:
      return writeBgeo(path, c);
    case ExportFormat::Ply:
      return writePly(path, c);
  }
}

}  // namespace

FrameExporter::FrameExporter(ExportOptions options) : options_(std::move(options)) {
  validateExportOptions(options_, "export");
  prepareExportFolder(options_.dir, options_.overwrite, options_.overwrite_option);
  for (ExportFormat f : options_.formats)
    if (f == ExportFormat::Vtk) {
      fluid_pvd_ = std::make_unique<PvdIndex>(options_.dir + "/fluid.pvd");
      control_pvd_ = std::make_unique<PvdIndex>(options_.dir + "/control.pvd");
    }
}

std::string FrameExporter::framePath(const char* prefix, long frame, const char* ext) const {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%05ld.%s", prefix, frame, ext);
  return options_.dir + "/" + name;
}

bool FrameExporter::due(double time, long step) const {
  if (frames_ == 0) return true;
  if (options_.every_steps > 0) return step - last_step_ >= options_.every_steps;
  if (step == last_step_) return false;
  // A millionth of a frame of slack for the rounding of the summed time steps.
  return (time - start_time_) * options_.fps >= double(frames_) - 1e-6;
}

void FrameExporter::write(const ParticleFrame& fr) {
  if (frames_ == 0) start_time_ = fr.time;
  last_step_ = fr.step;
  auto t0 = std::chrono::steady_clock::now();
  // Adds the time since t0 to `part` and restarts the clock.
  auto lap = [&](const char* part) {
    const auto t1 = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    t0 = t1;
    for (auto& [name, total] : ms_)
      if (name == part) return void(total += ms);
    ms_.emplace_back(part, ms);
  };
  for (ExportFormat f : options_.formats) {
    const std::string fluid = framePath("fluid", frames_, extension(f));
    const std::string control = framePath("control", frames_, extension(f));
    writeCloud(fluid, fluidCloud(fr, f), f);
    writeCloud(control, controlCloud(fr, f), f);
    if (f == ExportFormat::Vtk) {
      fluid_pvd_->add(fr.time, fluid.substr(options_.dir.size() + 1));
      control_pvd_->add(fr.time, control.substr(options_.dir.size() + 1));
    }
    lap(formatName(f));
  }
  const SurfaceOptions& so = options_.surface;
  if (so.enabled) {
    const FluidState& f = fr.fluid;
    const SurfaceMesh mesh = particleSurface(f.size(), f.x.data(), f.y.data(), f.z.data(), fr.spacing, so,
                                             so.vdb ? framePath("surface", frames_, "vdb") : "", fr.time);
    if (so.format == SurfaceMeshFormat::Obj)
      writeSurfaceObj(framePath("surface", frames_, "obj"), mesh, fr.time);
    else
      writeSurfacePly(framePath("surface", frames_, "ply"), mesh, fr.time);
    lap("surface");
  }
  ++frames_;
}

std::string FrameExporter::costReport() const {
  std::string out;
  char part[96];
  for (const auto& [name, total] : ms_) {
    std::snprintf(part, sizeof part, "%s%s %.2f", out.empty() ? "" : ", ", name.c_str(),
                  total / double(std::max(1L, frames_)));
    out += part;
  }
  return out.empty() ? out : out + " ms per frame";
}

}  // namespace ff
