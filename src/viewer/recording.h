// recording.h - the viewer's recording: frames exported the same way as
// `flowform run --export` (src/io/frame_exporter.h), started and stopped by
// the user (E key, or the panel's button). Each recording is a take of its
// own, in the first free folder BASE/take_NNN, so takes never mix and
// nothing in BASE is ever removed.
#pragma once
#include <memory>
#include <string>

#include "io/export_options.h"
#include "io/frame_exporter.h"
#include "sim/simulation.h"

namespace ff::viewer {

class Recording {
 public:
  // options.dir is the folder the takes go in ("flowform_recordings" if empty).
  void configure(ExportOptions options);
  const ExportOptions& options() const { return options_; }

  bool active() const { return exporter_ != nullptr; }
  // Starts a take in BASE/take_NNN and writes its first frame (the current
  // state). Returns the take's folder. Throws ff::Error (folder, disk); then
  // nothing is recording.
  std::string start(Simulation& sim);
  // Writes a frame if one is due (call after every step). Throws ff::Error;
  // the recording then stops.
  void afterStep(Simulation& sim);
  // Stops; returns a one-line summary ("" if nothing was recording).
  std::string stop();

  const std::string& folder() const { return folder_; }
  long frames() const { return exporter_ ? exporter_->frames() : 0; }

 private:
  ExportOptions options_;
  std::unique_ptr<FrameExporter> exporter_;
  std::string folder_;
};

}  // namespace ff::viewer
