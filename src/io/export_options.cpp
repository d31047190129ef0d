// export_options.cpp - parsing and checking export options.
#include "io/export_options.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "surface/particle_surface.h"

namespace ff {

const char* formatName(ExportFormat f) {
  switch (f) {
    case ExportFormat::Vtk:
      return "vtk";
    case ExportFormat::Bgeo:
      return "bgeo";
    case ExportFormat::Ply:
      return "ply";
  }
  return "?";
}

std::vector<ExportFormat> parseExportFormats(const std::string& list, const std::string& what) {
  static const char* const kChoices = " (one or more of vtk, bgeo, ply, comma-separated)";
  std::vector<ExportFormat> out;
  size_t start = 0;
  while (true) {
    const size_t comma = list.find(',', start);
    const std::string item =
        list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    bool found = false;
    for (ExportFormat f : {ExportFormat::Vtk, ExportFormat::Bgeo, ExportFormat::Ply}) {
      if (item != formatName(f)) continue;
      if (std::find(out.begin(), out.end(), f) != out.end())
        throw Error(what + ": format '" + item + "' is given twice");
      out.push_back(f);
      found = true;
    }
    if (!found) throw Error(what + ": unknown format '" + item + "'" + kChoices);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

void validateExportOptions(const ExportOptions& o, const std::string& what) {
  if (o.dir.empty()) throw Error(what + ": no export folder given");
  if (!(std::isfinite(o.fps) && o.fps > 0.0 && o.fps <= 10000.0))
    throw Error(what + ": fps must be in (0, 10000], got " + std::to_string(o.fps));
  if (o.every_steps < 0) throw Error(what + ": every_steps must be >= 0");
  if (o.formats.empty()) throw Error(what + ": no export format");
  if (o.surface.enabled) validateSurfaceOptions(o.surface, what + ": surface ");
}

}  // namespace ff
