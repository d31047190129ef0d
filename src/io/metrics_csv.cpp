// metrics_csv.cpp - the CSV metrics log.
#include "io/metrics_csv.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "core/error.h"

namespace ff {
namespace {

// A header cell, quoted when it holds a comma, a quote or a line break.
std::string cell(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

MetricsCsv::~MetricsCsv() {
  if (file_) std::fclose(file_);
}

void MetricsCsv::open(const std::string& path, const std::vector<std::string>& columns) {
  close();
  if (columns.empty()) throw Error(path + ": a metrics CSV needs at least one column");
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw Error(path + ": cannot create metrics CSV (" + std::strerror(errno) + ")");
  file_ = f;
  path_ = path;
  columns_ = columns.size();
  std::string line;
  for (size_t i = 0; i < columns.size(); ++i) line += (i ? "," : "") + cell(columns[i]);
  line += "\n";
  if (std::fputs(line.c_str(), file_) < 0 || std::fflush(file_) != 0)
    throw Error(path_ + ": cannot write metrics CSV (" + std::strerror(errno) + ")");
}

void MetricsCsv::resume(const std::string& path, const std::vector<std::string>& columns, double last_step) {
  std::string header;
  for (size_t i = 0; i < columns.size(); ++i) header += (i ? "," : "") + cell(columns[i]);
  std::vector<std::string> keep;
  {
    std::ifstream in(path);
    std::string line;
    if (!in || !std::getline(in, line) || line != header) return open(path, columns);
    keep.push_back(line);
    while (std::getline(in, line) && !in.eof()) {  // the last line must end with '\n'
      char* end = nullptr;
      const double step = std::strtod(line.c_str(), &end);
      if (end == line.c_str() || step > last_step) break;
      keep.push_back(line);
    }
  }
  close();
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw Error(path + ": cannot write metrics CSV (" + std::strerror(errno) + ")");
  file_ = f;
  path_ = path;
  columns_ = columns.size();
  for (const std::string& line : keep)
    if (std::fputs((line + "\n").c_str(), file_) < 0)
      throw Error(path_ + ": cannot write metrics CSV (" + std::strerror(errno) + ")");
  if (std::fflush(file_) != 0)
    throw Error(path_ + ": cannot write metrics CSV (" + std::strerror(errno) + ")");
}

void MetricsCsv::row(const std::vector<double>& values) {
  if (!file_) throw Error("metrics CSV: row() called before open()");
  if (values.size() != columns_)
    throw Error(path_ + ": metrics row has " + std::to_string(values.size()) + " values, expected " +
                std::to_string(columns_));
  std::string line;
  char buf[40];
  for (size_t i = 0; i < values.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.9g", values[i]);
    if (i) line += ',';
    line += buf;
  }
  line += '\n';
  if (std::fputs(line.c_str(), file_) < 0 || std::fflush(file_) != 0)
    throw Error(path_ + ": cannot write metrics CSV (" + std::strerror(errno) + ")");
}

void MetricsCsv::close() {
  if (!file_) return;
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0) throw Error(path_ + ": cannot close metrics CSV (" + std::strerror(errno) + ")");
}

}  // namespace ff
