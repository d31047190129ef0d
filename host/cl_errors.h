// cl_errors.h - OpenCL error codes as names, and the conversion of every
// OpenCL failure into an ff::Error that names the call and the code.
#pragma once
#include <CL/opencl.hpp>
#include <string>
#include <utility>

#include "core/error.h"

namespace ff {

// "CL_OUT_OF_RESOURCES" for -5, ..., "CL_UNKNOWN_ERROR" for codes not in the table.
const char* clErrorName(int code);

// "clEnqueueNDRangeKernel failed: CL_INVALID_WORK_GROUP_SIZE (-54)".
std::string clErrorText(const char* call, int code);

// Runs f(); an OpenCL failure (cl::Error) comes out as ff::Error
// "OpenCL: <what>: <call> failed: <CODE NAME> (<code>)". ff::Errors pass through.
template <class F>
auto clGuard(const std::string& what, F&& f) -> decltype(f()) {
  try {
    return std::forward<F>(f)();
  } catch (const cl::Error& e) {
    throw Error("OpenCL: " + what + ": " + clErrorText(e.what(), e.err()));
  }
}

}  // namespace ff
