// export_options.h - what a frame export writes, where and how often; shared
// by `flowform run`, `flowform render`, the viewer's recording and the Python
// module.
#pragma once
#include <string>
#include <vector>

#include "surface/surface_options.h"

namespace ff {

enum class ExportFormat { Vtk, Bgeo, Ply };

struct ExportOptions {
  std::string dir;       // the export folder
  double fps = 30.0;     // frames per simulated second
  long every_steps = 0;  // > 0: a frame every K steps instead (old --export-every)
  std::vector<ExportFormat> formats{ExportFormat::Vtk};  // at least one, each once
  bool overwrite = false;                        // remove another run's frames first (io/export_folder.h)
  std::string overwrite_option = "--overwrite";  // how the user asks for it, for the refusal's message
  SurfaceOptions surface;                        // surface meshes (and level sets), when enabled
};

// "vtk,bgeo,ply" (any order, comma-separated, each at most once) to formats.
// Throws ff::Error naming `what` (e.g. "--format") and the bad entry.
std::vector<ExportFormat> parseExportFormats(const std::string& list, const std::string& what);
const char* formatName(ExportFormat f);

// Throws ff::Error naming the bad field (prefixed by `what`).
void validateExportOptions(const ExportOptions& o, const std::string& what);

}  // namespace ff
