// export_cli.cpp - --export, --format, --fps, --export-every, --overwrite.
#include "app/export_cli.h"

namespace ff::app {

void addExportOptions(CLI::App* cmd, ExportOptions& o, std::string& formats, bool with_fps) {
  auto* ex = cmd->add_option("--export", o.dir,
                             "Write frames into this folder (refused if it holds another run's frames, "
                             "see --overwrite)");
  cmd->add_option("--format", formats, "Export formats, comma-separated: vtk, bgeo, ply (default vtk)")
      ->needs(ex);
  auto* every = cmd->add_option("--export-every", o.every_steps,
                                "Export a frame every K steps instead of at a frame rate")
                    ->needs(ex)
                    ->check(CLI::PositiveNumber);
  cmd->add_flag("--overwrite", o.overwrite,
                "Remove the frames of another run (files of flowform's frame naming only) from the "
                "export folder first")
      ->needs(ex);
  if (with_fps)
    cmd->add_option("--fps", o.fps, "Exported frames per simulated second (default 30)")
        ->needs(ex)
        ->excludes(every)
        ->check(CLI::Range(1e-3, 1e4));
}

}  // namespace ff::app
