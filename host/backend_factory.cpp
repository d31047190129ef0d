#include "host/backend_factory.h"

#include <cstdlib>

#include "core/error.h"
#include "cpu/backend_cpu.h"
#include "parallel/simd8.h"
#ifndef FF_NO_OPENCL
#include "host/backend_opencl.h"
#include "host/cl_context.h"
#endif

namespace ff {

#ifndef FF_NO_OPENCL
namespace {

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "none" : s;
}

std::string platformList() {
  try {
    return joined(listClPlatformNames());
  } catch (const Error&) {
    return "none";
  }
}

std::string firstLine(const std::string& s, const BackendNames& names) {
  const size_t nl = s.find('\n');
  return nl == std::string::npos ? s : s.substr(0, nl) + " ... (" + names.opencl + " shows all of it)";
}

}  // namespace
#endif

namespace {

std::string& chosenKernels() {
  static std::string choice;  // empty: not set by setKernelChoice
  return choice;
}

}  // namespace

bool knownKernels(const std::string& k) {
  return k == "auto" || k == "scalar" || k == "lanes";
}

void setKernelChoice(const std::string& name, const std::string& what) {
  if (!knownKernels(name))
    throw Error(what + ": unknown kernel variant '" + name + "' (known: auto, scalar, lanes)");
  chosenKernels() = name;
}

std::string kernelChoice() {
  if (!chosenKernels().empty()) return chosenKernels();
  const char* env = std::getenv("FLOWFORM_KERNELS");
  const std::string k = env && *env ? env : "auto";
  if (!knownKernels(k))
    throw Error("FLOWFORM_KERNELS: unknown kernel variant '" + k + "' (known: auto, scalar, lanes)");
  return k;
}

BackendNames pythonBackendNames() {
  return BackendNames{"backend", "device", "backend='opencl'", "backend='opencl' or 'auto'"};
}

std::unique_ptr<Backend> makeBackend(const std::string& kind, int device, int threads, std::string* note,
                                     const BackendNames& names) {
  if (note) note->clear();
  simd::isa();  // a bad $FLOWFORM_SIMD is refused here (the CPU's loops and metrics read it)
  if (kind != "auto" && kind != "cpu" && kind != "opencl")
    throw Error(names.backend + ": unknown backend '" + kind + "' (known: auto, cpu, opencl)");
  if (device < -1) throw Error(names.device + ": must be >= 0 (got " + std::to_string(device) + ")");
  if (kind == "cpu") {
    if (device >= 0)
      throw Error(names.device + ": only applies to the OpenCL backend (" + names.opencl_or_auto + ")");
    return std::make_unique<CpuBackend>(threads);
  }
#ifdef FF_NO_OPENCL
  if (kind == "opencl")
    throw Error(names.opencl + ": this flowform was built without OpenCL (FLOWFORM_OPENCL=OFF)");
  if (note) *note = "built without OpenCL; using the OpenMP CPU backend";
  return std::make_unique<CpuBackend>(threads);
#else
  if (kind == "opencl") {
    // A device that is not there: refused here, naming the caller's option
    // (ClContext names --device).
    const size_t n = device >= 0 ? listClDevices().size() : 0;
    if (device >= 0 && size_t(device) >= n)
      throw Error(names.device + " " + std::to_string(device) + ": no such OpenCL device; " +
                  (n == 0 ? std::string("there is none") : "the devices are 0.." + std::to_string(n - 1)) +
                  " (see `flowform devices`)");
    return std::make_unique<OpenClBackend>(device);
  }

  // auto: an OpenCL GPU (or the device asked for), else the CPU backend.
  std::string why;
  try {
    int pick = device;
    if (pick < 0) {
      for (const ClDeviceInfo& d : listClDevices())
        if (d.isGpu()) {
          pick = d.index;
          break;
        }
    }
    if (pick >= 0) return std::make_unique<OpenClBackend>(pick);
    why = "no OpenCL GPU found (platforms: " + platformList() + ")";
  } catch (const Error& e) {
    why = "OpenCL failed to start (" + firstLine(e.what(), names) + ")";
  }
  if (note) *note = why + "; using the OpenMP CPU backend";
  return std::make_unique<CpuBackend>(threads);
#endif
}

}  // namespace ff
