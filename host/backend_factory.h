// backend_factory.h - picks the backend for a run: `auto` (an OpenCL GPU when
// there is one, else the OpenMP CPU backend), `cpu` or `opencl`.
#pragma once
#include <memory>
#include <string>

#include "sim/backend.h"

namespace ff {

// kind: "auto", "cpu" or "opencl". device: index in `flowform devices` order,
// -1 = choose (opencl: the first GPU, else the first device). threads: OpenMP
// threads for the CPU backend (0 = OpenMP's default).
// `auto` falls back to the CPU backend when there is no OpenCL GPU, or when
// OpenCL is missing or fails to start, and says why in one line via *note
// (left empty when nothing needs saying). `opencl` throws ff::Error with that
// explanation instead; so does an unknown kind or a --device that cannot be used.
// The messages name the choices as `names` does: the CLI's options, or the
// Python module's keywords (pythonBackendNames).
struct BackendNames {
  std::string backend = "--backend";        // the choice of backend
  std::string device = "--device";          // the choice of device
  std::string opencl = "--backend opencl";  // the OpenCL backend, as the user asks for it
  std::string opencl_or_auto = "--backend opencl or auto";
};
BackendNames pythonBackendNames();  // backend=, device= of flowform.Simulation and flowform.resume
std::unique_ptr<Backend> makeBackend(const std::string& kind, int device, int threads, std::string* note,
                                     const BackendNames& names = BackendNames());

// --kernels: how the OpenCL backend maps particles to work-items. "scalar":
// one particle per work-item (for GPUs); "lanes": 8 per work-item as float8
// lanes (for CPU devices); "auto": by the device's type. The results are the
// same bit for bit. It applies to the OpenCL backends made after the call; the
// default is $FLOWFORM_KERNELS when set, else "auto". Throws ff::Error naming
// `what` for an unknown name.
void setKernelChoice(const std::string& name, const std::string& what = "--kernels");
std::string kernelChoice();

}  // namespace ff
