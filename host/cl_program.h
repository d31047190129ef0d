// cl_program.h - the kernels' OpenCL C source from the files embedded in the
// binary (kernels/*.cl, with `#include "ff_xxx.h"` resolved against the
// embedded kernels/common/ headers), and the program build with its log.
#pragma once
#include <CL/opencl.hpp>
#include <set>
#include <string>
#include <vector>

#include "host/cl_context.h"

namespace ff {

// The names of every embedded kernels/*.cl file, sorted.
std::vector<std::string> embeddedKernelFiles();

// The source of one embedded file with each `#include "name"` line replaced by
// the embedded kernels/common/name (recursively; a header already in
// `included` is left out, its include guard would skip it anyway). #line
// directives keep the build log's file names and line numbers right.
// Throws ff::Error naming the file and line of an include it cannot find.
std::string resolveKernelSource(const std::string& file, std::set<std::string>& included);

// GPU rounding, emulated on a CPU device (docs/GPU.md, "Rounding"). Every
// kernel file starts with `#pragma OPENCL FP_CONTRACT OFF`, so that a * b + c
// rounds twice, as in the C++ backend; a GPU compiler may still fuse it into
// one fused multiply-add. FLOWFORM_CL_GPU_ROUNDING (for tests) builds the
// kernels as such a compiler would:
//   contract: the pragmas switched to ON: a * b + c within one expression
//             becomes fma(a, b, c) (OpenCL C's default);
//   fuse-all: also -cl-unsafe-math-optimizations: products fuse with sums
//             across statements and functions too, and sums may be
//             reassociated (more than a GPU compiler without fast-math does).
// Unset or "off": the kernels as written. Any other value throws ff::Error.
enum class GpuRounding { Off, Contract, FuseAll };
GpuRounding gpuRoundingEmulation();

// Whether the kernels round exactly as the OpenMP backend on this device:
// PoCL (its compiler honours FP_CONTRACT OFF, its division and sqrt are
// correctly rounded) with no GPU rounding emulated. The equivalence tests
// compare bit for bit there, and within the GPU tolerances elsewhere.
bool roundsAsTheCpuBackend(const ClDeviceInfo& info);

// The build options for a device: OpenCL C 1.2, and correctly rounded
// division and sqrt where the device has them, so that the kernels' float
// arithmetic matches the CPU backend's (plus the fuse-all emulation's option).
std::string kernelBuildOptions(const ClDeviceInfo& info);

// The program source with the FP_CONTRACT OFF pragmas switched on when
// gpuRoundingEmulation() asks for it; unchanged otherwise.
std::string withGpuRoundingEmulation(std::string source);

// A build log for a message: all of a short log; of a long one the first
// lines that report errors (at most 12 lines, 2000 characters), and the whole
// log is written to TMPDIR/flowform_kernel_build_PID.log, whose path the text
// gives.
std::string shortBuildLog(const std::string& log);

// Builds one program from the given embedded .cl files (in order). A build
// failure throws ff::Error with the first errors of the device's build log
// (shortBuildLog).
cl::Program buildKernelProgram(const ClContext& cl, const std::vector<std::string>& files);

// Builds a program from OpenCL C source text, as buildKernelProgram does.
cl::Program buildProgramSource(const ClContext& cl, const std::string& source);

}  // namespace ff
