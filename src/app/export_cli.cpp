// export_cli.cpp - --export, --format, --fps, --export-every, --overwrite.
#include "app/export_cli.h"

namespace ff::app {

void addExportOptions(CLI::App* cmd, ExportOptions& o, std::string& formats, bool with_rate,
                      const std::string& export_help) {
  auto* ex = cmd->add_option("--export", o.dir, export_help);
  cmd->add_option("--format", formats, "Export formats, comma-separated: vtk, bgeo, ply (default vtk)")
      ->needs(ex);
  cmd->add_flag("--overwrite", o.overwrite,
                "Remove the frames of another run (files of flowform's frame naming only) from the "
                "export folder first")
      ->needs(ex);
  auto* surface = cmd->add_flag("--surface", o.surface.enabled,
                                "Also write the liquid's closed surface mesh per frame (surface_NNNNN.obj)")
                      ->needs(ex);
  cmd->add_option_function<std::string>(
         "--surface-format",
         [&o](const std::string& f) {
           o.surface.format = f == "ply" ? SurfaceMeshFormat::Ply : SurfaceMeshFormat::Obj;
         },
         "Surface mesh format: obj (default) or ply")
      ->check(CLI::IsMember({"obj", "ply"}))
      ->needs(surface);
  cmd->add_option("--surface-radius", o.surface.radius,
                  "Sphere radius per particle for the surface, in rest spacings (default 1)")
      ->needs(surface);
  cmd->add_option("--surface-voxel", o.surface.voxel,
                  "Level-set voxel size for the surface, in rest spacings (default 0.4)")
      ->needs(surface);
  cmd->add_option("--surface-smoothing", o.surface.smoothing,
                  "Mean-curvature smoothing iterations of the surface (default 1)")
      ->needs(surface);
  cmd->add_flag("--surface-vdb", o.surface.vdb, "Also write the surface's level set (surface_NNNNN.vdb)")
      ->needs(surface);
  if (with_rate) {
    auto* every = cmd->add_option("--export-every", o.every_steps,
                                  "Export a frame every K steps instead of at a frame rate")
                      ->needs(ex)
                      ->check(CLI::PositiveNumber);
    cmd->add_option("--fps", o.fps, "Exported frames per simulated second (default 30)")
        ->needs(ex)
        ->excludes(every)
        ->check(CLI::Range(1e-3, 1e4));
  }
}

}  // namespace ff::app
