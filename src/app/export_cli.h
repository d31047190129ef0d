// export_cli.h - the command-line options of a frame export (io/frame_exporter.h),
// shared by `flowform run` and `flowform render`.
#pragma once
#include <CLI/CLI.hpp>
#include <string>

#include "io/export_options.h"

namespace ff::app {

// Adds --export DIR (described by `export_help`), --format LIST (into
// `formats`, parsed later with parseExportFormats), --overwrite and, when
// `with_rate`, --fps and --export-every K (which exclude each other); and the
// surface options --surface,
// --surface-format, --surface-radius, --surface-voxel, --surface-smoothing,
// --surface-vdb.
void addExportOptions(CLI::App* cmd, ExportOptions& o, std::string& formats, bool with_rate,
                      const std::string& export_help);

}  // namespace ff::app
