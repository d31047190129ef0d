#include "host/cl_context.h"

#include "core/error.h"
#include "host/cl_errors.h"

namespace ff {

namespace {

// The platforms; an ICD loader with no platform reports CL_PLATFORM_NOT_FOUND_KHR.
std::vector<cl::Platform> platforms() {
  std::vector<cl::Platform> ps;
  try {
    cl::Platform::get(&ps);
  } catch (const cl::Error& e) {
    throw Error("OpenCL: no platform available (" + clErrorText(e.what(), e.err()) +
                "); install an OpenCL driver, e.g. the pocl-opencl-icd package");
  }
  if (ps.empty())
    throw Error("OpenCL: no platform available; install an OpenCL driver, e.g. pocl-opencl-icd");
  return ps;
}

// The devices of one platform (none is not an error).
std::vector<cl::Device> devicesOf(const cl::Platform& p) {
  std::vector<cl::Device> ds;
  try {
    p.getDevices(CL_DEVICE_TYPE_ALL, &ds);
  } catch (const cl::Error& e) {
    if (e.err() != CL_DEVICE_NOT_FOUND) throw;
    ds.clear();
  }
  return ds;
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\0' || s.back() == ' ' || s.back() == '\n')) s.pop_back();
  return s;
}

ClDeviceInfo describe(const cl::Device& d, const cl::Platform& p, int index, int platform_index) {
  ClDeviceInfo i;
  i.index = index;
  i.platform_index = platform_index;
  i.platform = trimmed(p.getInfo<CL_PLATFORM_NAME>());
  i.platform_version = trimmed(p.getInfo<CL_PLATFORM_VERSION>());
  i.name = trimmed(d.getInfo<CL_DEVICE_NAME>());
  i.vendor = trimmed(d.getInfo<CL_DEVICE_VENDOR>());
  i.version = trimmed(d.getInfo<CL_DEVICE_VERSION>());
  i.driver = trimmed(d.getInfo<CL_DRIVER_VERSION>());
  i.c_version = trimmed(d.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
  i.type = d.getInfo<CL_DEVICE_TYPE>();
  i.compute_units = d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
  i.max_work_group = d.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
  i.global_mem = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  i.local_mem = d.getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
  i.max_alloc = d.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  i.correctly_rounded_div_sqrt =
      (d.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
  return i;
}

// Walks every device in listClDevices() order.
template <class F>
void forEachDevice(F&& f) {
  int index = 0, pi = 0;
  for (const cl::Platform& p : platforms()) {
    for (const cl::Device& d : devicesOf(p)) f(d, p, index++, pi);
    ++pi;
  }
}

}  // namespace

std::string ClDeviceInfo::typeName() const {
  if (type & CL_DEVICE_TYPE_GPU) return "GPU";
  if (type & CL_DEVICE_TYPE_CPU) return "CPU";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  if (type & CL_DEVICE_TYPE_CUSTOM) return "custom";
  return "other";
}

std::string ClDeviceInfo::summary() const {
  return name + " (" + platform + "), " + typeName() + ", " + std::to_string(compute_units) +
         " compute units";
}

std::vector<ClDeviceInfo> listClDevices() {
  return clGuard("listing devices", [] {
    std::vector<ClDeviceInfo> out;
    forEachDevice([&](const cl::Device& d, const cl::Platform& p, int index, int pi) {
      out.push_back(describe(d, p, index, pi));
    });
    return out;
  });
}

std::vector<std::string> listClPlatformNames() {
  return clGuard("listing platforms", [] {
    std::vector<std::string> out;
    for (const cl::Platform& p : platforms()) out.push_back(trimmed(p.getInfo<CL_PLATFORM_NAME>()));
    return out;
  });
}

ClContext::ClContext(int device_index) {
  clGuard("opening the device", [&] {
    std::vector<std::pair<cl::Device, ClDeviceInfo>> all;
    forEachDevice([&](const cl::Device& d, const cl::Platform& p, int index, int pi) {
      all.emplace_back(d, describe(d, p, index, pi));
    });
    if (all.empty())
      throw Error("OpenCL: the platforms (" + std::to_string(listClPlatformNames().size()) +
                  ") offer no device");
    int pick = -1;
    if (device_index >= 0) {
      if (device_index >= int(all.size()))
        throw Error("--device " + std::to_string(device_index) +
                    ": no such OpenCL device; the devices are 0.." + std::to_string(all.size() - 1) +
                    " (see `flowform devices`)");
      pick = device_index;
    } else {
      for (size_t i = 0; i < all.size() && pick < 0; ++i)
        if (all[i].second.isGpu()) pick = int(i);
      if (pick < 0) pick = 0;
    }
    device_ = all[size_t(pick)].first;
    info_ = all[size_t(pick)].second;
    context_ = cl::Context(device_);
    queue_ = cl::CommandQueue(context_, device_);
  });
}

}  // namespace ff
