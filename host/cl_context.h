// cl_context.h - OpenCL platforms and devices, and the context + in-order
// queue on the one device a run uses.
#pragma once
#include <CL/opencl.hpp>
#include <string>
#include <vector>

namespace ff {

// One device, with the limits the backend sizes its launches by.
struct ClDeviceInfo {
  int index = 0;  // position in listClDevices() order (what --device N picks)
  int platform_index = 0;
  std::string platform, platform_version;
  std::string name, vendor, version, driver, c_version;
  cl_device_type type = 0;
  cl_uint compute_units = 0;
  size_t max_work_group = 0;
  cl_ulong global_mem = 0, local_mem = 0, max_alloc = 0;
  bool correctly_rounded_div_sqrt = false;  // CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT
  bool isGpu() const { return (type & CL_DEVICE_TYPE_GPU) != 0; }
  std::string typeName() const;  // "GPU", "CPU", "accelerator", ...
  std::string summary() const;   // "NAME (PLATFORM), GPU, 132 compute units"
};

// Every device of every platform, platforms in the ICD loader's order and
// devices in each platform's order. Throws ff::Error explaining why when
// OpenCL is missing (no ICD loader platform) or a query fails.
std::vector<ClDeviceInfo> listClDevices();
// The platform names, for messages ("" list when OpenCL is missing).
std::vector<std::string> listClPlatformNames();

// The context and in-order command queue on one device.
class ClContext {
 public:
  // device_index < 0: the first GPU, else the first device.
  explicit ClContext(int device_index);
  const cl::Context& context() const { return context_; }
  const cl::Device& device() const { return device_; }
  cl::CommandQueue& queue() { return queue_; }
  const ClDeviceInfo& info() const { return info_; }

 private:
  cl::Context context_;
  cl::Device device_;
  cl::CommandQueue queue_;
  ClDeviceInfo info_;
};

}  // namespace ff
