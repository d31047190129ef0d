// cl_kernel.h - a kernel with launch sizes taken from the device's limits
// (CL_DEVICE_MAX_WORK_GROUP_SIZE, the kernel's CL_KERNEL_WORK_GROUP_SIZE and
// preferred multiple), argument setting, launches, and device buffers.
#pragma once
#include <CL/opencl.hpp>
#include <cstddef>
#include <string>
#include <vector>

#include "core/error.h"
#include "host/cl_context.h"
#include "host/cl_errors.h"
#include "sim/backend.h"

namespace ff {

struct ClKernel {
  cl::Kernel kernel;
  std::string name;
  size_t local = 1;       // work-group size for per-item kernels
  size_t pow2_local = 1;  // power-of-two work-group size for reductions
};

// Creates kernel `name` from `program`; work-group sizes at most `cap`, and for
// reductions small enough that `local_bytes_per_item` bytes per work-item fit
// in the device's local memory.
ClKernel makeKernel(const cl::Program& program, const char* name, const ClContext& cl, size_t cap = 256,
                    size_t local_bytes_per_item = 0);

template <class... A>
void setKernelArgs(ClKernel& k, const A&... args) {
  cl_uint i = 0;
  try {
    (k.kernel.setArg(i++, args), ...);
  } catch (const cl::Error& e) {
    throw Error("OpenCL: kernel '" + k.name + "' argument " + std::to_string(i - 1) + ": " +
                clErrorText(e.what(), e.err()));
  }
}

// Enqueues `global` work-items in groups of `local` (global a multiple of local).
void enqueueKernel(cl::CommandQueue& q, ClKernel& k, size_t global, size_t local);

// One work-item per element 0..n-1 (the kernel checks its index against n).
template <class... A>
void launch(cl::CommandQueue& q, ClKernel& k, size_t n, const A&... args) {
  if (n == 0) return;
  setKernelArgs(k, args...);
  enqueueKernel(q, k, (n + k.local - 1) / k.local * k.local, k.local);
}

// `groups` work-groups of `local` work-items (reductions, block scans).
template <class... A>
void launchGroups(cl::CommandQueue& q, ClKernel& k, size_t groups, size_t local, const A&... args) {
  if (groups == 0) return;
  setKernelArgs(k, args...);
  enqueueKernel(q, k, groups * local, local);
}

// FLOWFORM_CL_POISON=1: every new device buffer starts filled with NaN (as a
// GPU's uninitialised memory may), so that a kernel reading a value that was
// never written shows up on PoCL, which zeroes new memory.
bool clPoisonEnabled();

// A device buffer that only grows; zero-sized requests allocate one element
// (OpenCL has no empty buffers). Its contents start undefined (NaN under
// FLOWFORM_CL_POISON=1), and are lost when it grows.
class DeviceBuffer {
 public:
  void ensure(const cl::Context& ctx, size_t bytes);
  const cl::Buffer& get() const { return buf_; }
  size_t capacity() const { return bytes_; }

 private:
  cl::Buffer buf_;
  size_t bytes_ = 0;
};

template <class T>
void upload(cl::CommandQueue& q, const cl::Context& ctx, DeviceBuffer& b, const std::vector<T>& v) {
  b.ensure(ctx, v.size() * sizeof(T));
  if (!v.empty()) q.enqueueWriteBuffer(b.get(), CL_FALSE, 0, v.size() * sizeof(T), v.data());
}

// Host synchronisations of every queue since the program started (a
// process-wide count; callers take differences).
Backend::HostSyncs& clHostSyncs();

// A blocking read (counted).
inline void blockingRead(cl::CommandQueue& q, const cl::Buffer& b, size_t bytes, void* out) {
  ++clHostSyncs().reads;
  q.enqueueReadBuffer(b, CL_TRUE, 0, bytes, out);
}
// Waits for everything enqueued on q (counted).
inline void finishQueue(cl::CommandQueue& q) {
  ++clHostSyncs().waits;
  q.finish();
}

template <class T>
void download(cl::CommandQueue& q, const DeviceBuffer& b, size_t n, std::vector<T>& v) {
  v.resize(n);
  if (n) blockingRead(q, b.get(), n * sizeof(T), v.data());
}

template <class T>
void fillBuffer(cl::CommandQueue& q, const DeviceBuffer& b, T value, size_t n, size_t offset = 0) {
  if (n) q.enqueueFillBuffer(b.get(), value, offset * sizeof(T), n * sizeof(T));
}

inline cl_float4 f4(float a, float b, float c, float d) {
  cl_float4 v;
  v.s[0] = a, v.s[1] = b, v.s[2] = c, v.s[3] = d;
  return v;
}
inline cl_int4 i4(int a, int b, int c, int d) {
  cl_int4 v;
  v.s[0] = a, v.s[1] = b, v.s[2] = c, v.s[3] = d;
  return v;
}

}  // namespace ff
