// pvd_index.h - a ParaView collection (.pvd): the files of a time series with
// their simulated times, so that ParaView's time axis shows real seconds.
// The whole index is rewritten (atomically) after every added frame, so an
// interrupted run still leaves a valid index of the frames it wrote.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace ff {

class PvdIndex {
 public:
  explicit PvdIndex(std::string path) : path_(std::move(path)) {}
  // Adds `file` (a name relative to the index's folder) at `time` seconds
  // and rewrites the index. Throws ff::Error naming the path.
  void add(double time, const std::string& file);
  const std::string& path() const { return path_; }
  size_t size() const { return entries_.size(); }

 private:
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace ff
