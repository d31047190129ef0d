// bench_report.cpp - markdown, CSV and plots of bench results.
#include "app/bench_report.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/embedded.h"
#include "core/error.h"

namespace ff::app {

namespace {

// Quotes a CSV field when it holds a comma, a quote or a newline.
std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q += "'\\''";
    else
      q += c;
  }
  return q + "'";
}

}  // namespace

void printMarkdown(std::FILE* out, const std::string& title, const std::vector<BenchResult>& results) {
  if (results.empty()) return;
  std::fprintf(out, "\n### %s (ms per step: median over %d steps)\n\n", title.c_str(), results.front().steps);
  std::fprintf(out, "| scene | backend | device | fluid | control |");
  for (int p = 0; p < int(Phase::Count); ++p) std::fprintf(out, " %s |", phaseName(Phase(p)));
  std::fprintf(out, " **total** | total min-max | substeps | B/particle |\n");
  std::fprintf(out, "|---|---|---|---:|---:|");
  for (int p = 0; p < int(Phase::Count); ++p) std::fprintf(out, "---:|");
  std::fprintf(out, "---:|---:|---:|---:|\n");
  for (const BenchResult& r : results) {
    std::fprintf(out, "| %s | %s | %s | %ld | %ld |", r.scene.c_str(), r.backend.c_str(), r.device.c_str(),
                 r.fluid, r.control);
    for (int p = 0; p < int(Phase::Count); ++p) std::fprintf(out, " %.3f |", r.phase[size_t(p)].median);
    std::fprintf(out, " **%.2f** | %.2f-%.2f | %.2f | %.0f |\n", r.total.median, r.total.min, r.total.max,
                 r.mean_substeps, r.fluid > 0 ? double(r.memory_bytes) / double(r.fluid) : 0.0);
  }
  bool stages = false;
  for (const BenchResult& r : results) stages = stages || !r.stages.empty();
  if (stages) {
    std::fprintf(out, "\nStages inside the phases (ms per step, mean):\n\n");
    std::fprintf(out, "| scene | backend | fluid | phase | stage | ms |\n|---|---|---:|---|---|---:|\n");
    for (const BenchResult& r : results)
      for (const StageTime& s : r.stages)
        std::fprintf(out, "| %s | %s | %ld | %s | %s | %.3f |\n", r.scene.c_str(), r.backend.c_str(), r.fluid,
                     s.phase.c_str(), s.name.c_str(), s.ms);
  }
  std::fflush(out);
}

void writeBenchCsv(const std::string& path, const std::vector<BenchResult>& results) {
  std::ofstream f(path);
  if (!f) throw Error(path + ": cannot write the CSV (" + std::strerror(errno) + ")");
  f << "scene,backend,device,fluid,control,phase,ms_median,ms_min,ms_max\n";
  auto row = [&](const BenchResult& r, const std::string& phase, const PhaseStats& s) {
    f << csvField(r.scene) << ',' << csvField(r.backend) << ',' << csvField(r.device) << ',' << r.fluid << ','
      << r.control << ',' << phase << ',' << s.median << ',' << s.min << ',' << s.max << '\n';
  };
  for (const BenchResult& r : results) {
    for (int p = 0; p < int(Phase::Count); ++p) row(r, phaseName(Phase(p)), r.phase[size_t(p)]);
    row(r, "total", r.total);
    // The named stages inside the phases are timed as a mean per step: that
    // mean in ms_median, min and max left empty.
    for (const StageTime& st : r.stages)
      f << csvField(r.scene) << ',' << csvField(r.backend) << ',' << csvField(r.device) << ',' << r.fluid
        << ',' << r.control << ',' << csvField(st.phase + "/" + st.name) << ',' << st.ms << ",,\n";
  }
  f.flush();
  if (!f) throw Error(path + ": writing the CSV failed (" + std::strerror(errno) + ")");
}

std::vector<std::string> plotBenchCsv(const std::string& csv_path) {
  namespace fs = std::filesystem;
  const fs::path csv(csv_path);
  const fs::path stem = csv.parent_path() / csv.stem();
  const fs::path script =
      fs::temp_directory_path() / ("flowform_plot_bench_" + std::to_string(::getpid()) + ".py");
  {
    std::ofstream s(script);
    if (!s) throw Error(script.string() + ": cannot write the plot script");
    s << embeddedFile("src/app/plot_bench.py");
  }
  // The python3 on PATH first; Debian's own next, since a python3 on PATH
  // (pyenv, a venv) often lacks Debian's python3-matplotlib.
  std::vector<std::string> written;
  int code = 127;
  for (const char* python : {"python3", "/usr/bin/python3"}) {
    const std::string cmd = std::string(python) + " " + shellQuote(script.string()) + " " +
                            shellQuote(csv.string()) + " " + shellQuote(stem.string()) + " 2>&1";
    std::FILE* p = ::popen(cmd.c_str(), "r");
    if (!p) continue;
    std::vector<std::string> lines;
    char line[4096];
    while (std::fgets(line, sizeof line, p)) {
      std::string l(line);
      while (!l.empty() && (l.back() == '\n' || l.back() == '\r')) l.pop_back();
      if (!l.empty()) lines.push_back(l);
    }
    const int status = ::pclose(p);
    code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code == 0) {
      for (const std::string& l : lines)
        if (l.rfind("wrote ", 0) == 0) written.push_back(l.substr(6));
      break;
    }
    if (code == 127 || code == 3) continue;  // no such python3, or no matplotlib in it: try the next
    std::string tail;
    for (size_t i = lines.size() > 5 ? lines.size() - 5 : 0; i < lines.size(); ++i) tail += "\n  " + lines[i];
    std::error_code ec;
    fs::remove(script, ec);
    throw Error("--plot: the plot script failed on " + csv_path + " (exit " + std::to_string(code) +
                "):" + tail);
  }
  std::error_code ec;
  fs::remove(script, ec);
  if (code == 127) throw Error("--plot needs python3 with matplotlib: apt-get install python3-matplotlib");
  if (code == 3) throw Error("--plot needs matplotlib for python3: apt-get install python3-matplotlib");
  return written;
}

}  // namespace ff::app
