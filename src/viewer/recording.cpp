// recording.cpp - start/stop recording takes from the viewer.
#include "viewer/recording.h"

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "sim/export_frame.h"

namespace ff::viewer {

void Recording::configure(ExportOptions options) {
  stop();
  if (options.dir.empty()) options.dir = "flowform_recordings";
  validateExportOptions(options, "recording");
  options_ = std::move(options);
}

std::string Recording::start(Simulation& sim) {
  stop();
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(options_.dir, ec);
  if (ec) throw Error(options_.dir + ": cannot create the recording folder: " + ec.message());
  for (int take = 1; take <= 9999; ++take) {
    char name[32];
    std::snprintf(name, sizeof name, "take_%03d", take);
    const fs::path dir = fs::path(options_.dir) / name;
    if (fs::exists(dir, ec)) continue;
    ExportOptions o = options_;
    o.dir = dir.string();
    o.overwrite = false;
    try {
      exporter_ = std::make_unique<FrameExporter>(o);
      folder_ = o.dir;
      exportFrameIfDue(sim, *exporter_);
    } catch (...) {
      exporter_.reset();
      throw;
    }
    return folder_;
  }
  throw Error(options_.dir + ": no free take_NNN folder left (9999 takes)");
}

void Recording::afterStep(Simulation& sim) {
  if (!exporter_) return;
  try {
    exportFrameIfDue(sim, *exporter_);
  } catch (...) {
    exporter_.reset();
    throw;
  }
}

std::string Recording::stop() {
  if (!exporter_) return "";
  const std::string summary = "recorded " + std::to_string(exporter_->frames()) + " frames into " + folder_ +
                              " (" + exporter_->costReport() + ")";
  exporter_.reset();
  return summary;
}

}  // namespace ff::viewer
