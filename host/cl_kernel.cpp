#include "host/cl_kernel.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

namespace ff {

ClKernel makeKernel(const cl::Program& program, const char* name, const ClContext& cl, size_t cap,
                    size_t local_bytes_per_item) {
  ClKernel k;
  k.name = name;
  try {
    k.kernel = cl::Kernel(program, name);
    const size_t kmax = k.kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(cl.device());
    const size_t mult = k.kernel.getWorkGroupInfo<CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE>(cl.device());
    size_t limit = std::min({kmax, cl.info().max_work_group, cap});
    if (local_bytes_per_item > 0) {
      const size_t used = k.kernel.getWorkGroupInfo<CL_KERNEL_LOCAL_MEM_SIZE>(cl.device());
      const size_t room = cl.info().local_mem > used ? size_t(cl.info().local_mem - used) : 0;
      limit = std::min(limit, room / local_bytes_per_item);
    }
    limit = std::max<size_t>(limit, 1);
    k.local = mult > 0 && limit >= mult ? limit - limit % mult : limit;
    k.pow2_local = 1;
    while (k.pow2_local * 2 <= limit) k.pow2_local *= 2;
  } catch (const cl::Error& e) {
    throw Error(std::string("OpenCL: kernel '") + name + "': " + clErrorText(e.what(), e.err()));
  }
  return k;
}

void enqueueKernel(cl::CommandQueue& q, ClKernel& k, size_t global, size_t local) {
  try {
    q.enqueueNDRangeKernel(k.kernel, cl::NullRange, cl::NDRange(global), cl::NDRange(local));
  } catch (const cl::Error& e) {
    throw Error("OpenCL: kernel '" + k.name + "' (" + std::to_string(global) + " work-items in groups of " +
                std::to_string(local) + "): " + clErrorText(e.what(), e.err()));
  }
}

bool clPoisonEnabled() {
  const char* v = std::getenv("FLOWFORM_CL_POISON");
  if (!v || !*v || std::strcmp(v, "0") == 0) return false;
  if (std::strcmp(v, "1") == 0) return true;
  // Not silently off: "yes" or "true" read as off would hide what the check is for.
  throw Error(std::string("FLOWFORM_CL_POISON: must be 1 (on) or 0 (off), got '") + v + "'");
}

Backend::HostSyncs& clHostSyncs() {
  static Backend::HostSyncs count;
  return count;
}

void DeviceBuffer::ensure(const cl::Context& ctx, size_t bytes) {
  bytes = std::max<size_t>(bytes, 16);
  if (bytes <= bytes_) return;
  if (clPoisonEnabled()) {
    // Quiet NaNs in every word, as a GPU's uninitialised memory may hold anything.
    std::vector<float> nan((bytes + sizeof(float) - 1) / sizeof(float),
                           std::numeric_limits<float>::quiet_NaN());
    buf_ = cl::Buffer(ctx, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, nan.data());
  } else {
    buf_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, bytes);
  }
  bytes_ = bytes;
}

}  // namespace ff
