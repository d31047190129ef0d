// metrics_csv.h - a CSV log of per-step metrics: a header line, then one row
// per call, each flushed at once so that a crashed run leaves a readable file.
#pragma once
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

namespace ff {

class MetricsCsv {
 public:
  MetricsCsv() = default;
  ~MetricsCsv();
  MetricsCsv(const MetricsCsv&) = delete;
  MetricsCsv& operator=(const MetricsCsv&) = delete;

  // Creates (truncates) `path` and writes the header. Throws ff::Error naming
  // the path if it cannot. Closes any file opened before.
  void open(const std::string& path, const std::vector<std::string>& columns);
  // Continues the log of a resumed run: if `path` holds a log with the same
  // columns, keeps its header and the rows up to step `last_step` (the first
  // column), drops later ones (a run killed after its last checkpoint) and
  // appends from there; otherwise like open().
  void resume(const std::string& path, const std::vector<std::string>& columns, double last_step);
  // One row, values printed with %.9g; there must be one value per column.
  void row(const std::vector<double>& values);
  template <class... T, class = std::enable_if_t<(std::is_arithmetic_v<T> && ...)>>
  void row(T... values) {
    row(std::vector<double>{double(values)...});
  }
  void close();

  bool isOpen() const { return file_ != nullptr; }
  const std::string& path() const { return path_; }
  size_t columns() const { return columns_; }

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  size_t columns_ = 0;
};

}  // namespace ff
