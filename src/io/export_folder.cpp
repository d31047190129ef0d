// export_folder.cpp - refuse or clean a folder holding another run's frames.
#include "io/export_folder.h"

#include <algorithm>
#include <filesystem>
#include <regex>

#include "core/error.h"

namespace ff {

namespace fs = std::filesystem;

bool isFrameFileName(const std::string& name) {
  static const std::regex frame(
      "(fluid|control|surface)(_[0-9]+\\.(vtu|bgeo|ply|obj|vdb|pcache)|\\.pvd)(\\.tmp)?");
  return std::regex_match(name, frame);
}

void prepareExportFolder(const std::string& dir, bool overwrite, const std::string& overwrite_option) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create export folder: " + ec.message());
  if (!fs::is_directory(dir, ec)) throw Error(dir + ": the export path is not a folder");
  std::vector<fs::path> old;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (isFrameFileName(it->path().filename().string()) && !it->is_directory()) old.push_back(it->path());
  if (ec) throw Error(dir + ": cannot read export folder: " + ec.message());
  if (old.empty()) return;
  std::sort(old.begin(), old.end());
  if (!overwrite)
    throw Error(dir + ": the export folder already holds frames of another run (" +
                old.front().filename().string() + " and " + std::to_string(old.size() - 1) +
                " more); pick an empty folder, or pass " + overwrite_option +
                " to remove those frames first");
  for (const fs::path& p : old)
    if (!fs::remove(p, ec) && ec) throw Error(p.string() + ": cannot remove old frame: " + ec.message());
}

}  // namespace ff
