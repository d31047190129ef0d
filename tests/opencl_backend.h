// opencl_backend.h - the OpenCL backend on the default device for the tests
// (the first GPU, else the first device: PoCL here). No OpenCL platform is a
// test failure, not a skip: PoCL (pocl-opencl-icd) is a declared dependency
// that .ci/setup installs.
#pragma once
#include <gtest/gtest.h>

#include <memory>

#include "core/error.h"
#include "host/backend_opencl.h"

namespace fftest {

inline std::unique_ptr<ff::OpenClBackend> openClBackend() {
  try {
    return std::make_unique<ff::OpenClBackend>(-1);
  } catch (const ff::Error& e) {
    ADD_FAILURE() << "the OpenCL backend did not start: " << e.what()
                  << "\n(PoCL, package pocl-opencl-icd, is a declared dependency; .ci/setup installs it)";
    return nullptr;
  }
}

}  // namespace fftest
