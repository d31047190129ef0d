#include "host/cl_program.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/embedded.h"
#include "core/error.h"
#include "host/cl_errors.h"

namespace ff {

namespace {

const char* kKernelDir = "kernels/";
const char* kCommonDir = "kernels/common/";

bool startsWith(const std::string& s, const std::string& p) {
  return s.compare(0, p.size(), p) == 0;
}
bool endsWith(const std::string& s, const std::string& p) {
  return s.size() >= p.size() && s.compare(s.size() - p.size(), p.size(), p) == 0;
}

bool isEmbedded(const std::string& name) {
  for (const EmbeddedFile* f = resources_files(); f->name; ++f)
    if (name == f->name) return true;
  return false;
}

// If `line` is `#include "name"` (spaces allowed), returns true and the name.
bool includeName(const std::string& line, std::string& name) {
  size_t i = line.find_first_not_of(" \t");
  if (i == std::string::npos || line[i] != '#') return false;
  i = line.find_first_not_of(" \t", i + 1);
  if (i == std::string::npos || line.compare(i, 7, "include") != 0) return false;
  const size_t q0 = line.find('"', i + 7);
  const size_t q1 = q0 == std::string::npos ? q0 : line.find('"', q0 + 1);
  if (q1 == std::string::npos) return false;
  name = line.substr(q0 + 1, q1 - q0 - 1);
  return true;
}

void resolveInto(const std::string& file, std::set<std::string>& included, std::ostringstream& out,
                 int depth) {
  if (depth > 16) throw Error(file + ": #include nesting deeper than 16 (a cycle?)");
  const std::string text = embeddedFile(file);
  std::istringstream in(text);
  std::string line;
  int number = 0;
  out << "#line 1 \"" << file << "\"\n";
  while (std::getline(in, line)) {
    ++number;
    std::string name;
    if (!includeName(line, name)) {
      out << line << '\n';
      continue;
    }
    const std::string header = kCommonDir + name;
    if (!isEmbedded(header))
      throw Error(file + ":" + std::to_string(number) + ": #include \"" + name + "\": no embedded header '" +
                  header + "' (kernels/common/*.h are embedded at build time)");
    if (included.insert(header).second) resolveInto(header, included, out, depth + 1);
    out << "#line " << number + 1 << " \"" << file << "\"\n";
  }
}

}  // namespace

std::vector<std::string> embeddedKernelFiles() {
  std::vector<std::string> out;
  for (const EmbeddedFile* f = resources_files(); f->name; ++f) {
    const std::string n = f->name;
    if (startsWith(n, kKernelDir) && !startsWith(n, kCommonDir) && endsWith(n, ".cl")) out.push_back(n);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string resolveKernelSource(const std::string& file, std::set<std::string>& included) {
  std::ostringstream out;
  resolveInto(file, included, out, 0);
  return out.str();
}

GpuRounding gpuRoundingEmulation() {
  const char* v = std::getenv("FLOWFORM_CL_GPU_ROUNDING");
  if (!v || !*v || std::string(v) == "off") return GpuRounding::Off;
  if (std::string(v) == "contract") return GpuRounding::Contract;
  if (std::string(v) == "fuse-all") return GpuRounding::FuseAll;
  throw Error(std::string("FLOWFORM_CL_GPU_ROUNDING: '") + v + "' is not one of off, contract, fuse-all");
}

bool roundsAsTheCpuBackend(const ClDeviceInfo& info) {
  return info.platform == "Portable Computing Language" && (info.type & CL_DEVICE_TYPE_CPU) != 0 &&
         info.correctly_rounded_div_sqrt && gpuRoundingEmulation() == GpuRounding::Off;
}

std::string kernelBuildOptions(const ClDeviceInfo& info) {
  std::string opt = "-cl-std=CL1.2";
  if (info.correctly_rounded_div_sqrt) opt += " -cl-fp32-correctly-rounded-divide-sqrt";
  if (gpuRoundingEmulation() == GpuRounding::FuseAll) opt += " -cl-unsafe-math-optimizations";
  return opt;
}

std::string withGpuRoundingEmulation(std::string source) {
  if (gpuRoundingEmulation() == GpuRounding::Off) return source;
  const std::string off = "#pragma OPENCL FP_CONTRACT OFF", on = "#pragma OPENCL FP_CONTRACT ON ";
  for (size_t at = source.find(off); at != std::string::npos; at = source.find(off, at + off.size()))
    source.replace(at, off.size(), on);
  return source;
}

std::string shortBuildLog(const std::string& log) {
  constexpr size_t kMaxLines = 12, kMaxChars = 2000;
  // The first lines that report an error, with the line after each (the
  // source line the compiler quotes); all of the log if it is short.
  std::vector<std::string> lines;
  {
    std::istringstream in(log);
    std::string line;
    while (std::getline(in, line)) lines.push_back(line);
  }
  std::string head;
  size_t shown = 0;
  for (size_t i = 0; i < lines.size() && shown < kMaxLines; ++i) {
    if (lines.size() > kMaxLines && lines[i].find("error") == std::string::npos) continue;
    for (size_t k = i; k < std::min(lines.size(), i + (lines.size() > kMaxLines ? 2 : 1)); ++k, ++shown)
      head += lines[k] + "\n";
  }
  if (head.size() > kMaxChars) head = head.substr(0, kMaxChars) + "...\n";
  if (log.size() <= head.size()) return "build log:\n" + log;
  // Keep the whole log in a file the message names.
  std::error_code ec;
  const std::filesystem::path file = std::filesystem::temp_directory_path(ec) /
                                     ("flowform_kernel_build_" + std::to_string(::getpid()) + ".log");
  std::ofstream out(file, std::ios::binary);
  out << log;
  const std::string where =
      out.good() ? "the full log (" + std::to_string(log.size()) + " bytes) is in " + file.string()
                 : "the full log could not be written to " + file.string();
  return "first errors of the build log (" + where + "):\n" + head;
}

cl::Program buildKernelProgram(const ClContext& cl, const std::vector<std::string>& files) {
  std::set<std::string> included;
  std::string source;
  for (const std::string& f : files) source += resolveKernelSource(f, included);
  return buildProgramSource(cl, withGpuRoundingEmulation(source));
}

cl::Program buildProgramSource(const ClContext& cl, const std::string& source) {
  cl::Program program =
      clGuard("creating the kernel program", [&] { return cl::Program(cl.context(), source); });
  const std::string options = kernelBuildOptions(cl.info());
  auto buildLog = [&] {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(cl.device());
    } catch (const cl::Error&) {
      log = "(the device gave no build log)";
    }
    while (!log.empty() && (log.back() == '\n' || log.back() == '\0')) log.pop_back();
    return log;
  };
  try {
    program.build(std::vector<cl::Device>{cl.device()}, options.c_str());
  } catch (const cl::Error& e) {
    const std::string log = buildLog();
    throw Error("OpenCL: building the kernels for " + cl.info().name + " with \"" + options +
                "\": " + clErrorText(e.what(), e.err()) + "; " + shortBuildLog(log));
  }
  // FLOWFORM_CL_BUILD_LOG=FILE: the device, the options and the compiler's log
  // of a successful build too (bench/gpu_check.sh keeps it).
  if (const char* path = std::getenv("FLOWFORM_CL_BUILD_LOG"); path && *path) {
    std::ofstream f(path, std::ios::app);
    if (!f) throw Error(std::string("FLOWFORM_CL_BUILD_LOG: cannot write ") + path);
    f << "device: " << cl.info().summary() << "\noptions: " << options << "\nbuild log:\n"
      << buildLog() << "\n\n";
  }
  return program;
}

}  // namespace ff
