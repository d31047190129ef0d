// cmd_devices.cpp - `flowform devices`: the OpenCL platforms and devices, in
// the order `flowform run --device N` numbers them, with their limits.
#include <cstdio>
#include <string>

#include "app/commands.h"
#include "app/kernels_option.h"
#include "core/error.h"
#ifndef FF_NO_OPENCL
#include "host/backend_factory.h"
#include "host/cl_context.h"
#endif

namespace ff::app {

namespace {

#ifdef FF_NO_OPENCL
int listDevices() {
  std::printf(
      "this flowform was built without OpenCL (FLOWFORM_OPENCL=OFF); `flowform run` uses the OpenMP CPU "
      "backend\n");
  return 0;
}
#else
std::string mib(cl_ulong bytes) {
  char buf[32];
  if (bytes >= (cl_ulong(1) << 30))
    std::snprintf(buf, sizeof buf, "%.1f GiB", double(bytes) / double(cl_ulong(1) << 30));
  else
    std::snprintf(buf, sizeof buf, "%.0f KiB", double(bytes) / 1024.0);
  return buf;
}

int listDevices() {
  std::vector<ClDeviceInfo> devices;
  try {
    devices = listClDevices();
  } catch (const Error& e) {
    std::printf("no OpenCL devices: %s\n", e.what());
    std::printf("`flowform run` uses the OpenMP CPU backend (--backend cpu, or auto).\n");
    return 0;
  }
  int platform = -1;
  for (const ClDeviceInfo& d : devices) {
    if (d.platform_index != platform) {
      platform = d.platform_index;
      std::printf("platform %d: %s (%s)\n", platform, d.platform.c_str(), d.platform_version.c_str());
    }
    std::printf("  device %d: %s [%s]\n", d.index, d.name.c_str(), d.typeName().c_str());
    std::printf("    vendor %s, %s, driver %s, %s\n", d.vendor.c_str(), d.version.c_str(), d.driver.c_str(),
                d.c_version.c_str());
    std::printf(
        "    compute units %u, max work-group size %zu, global memory %s (max allocation %s), local memory "
        "%s\n",
        unsigned(d.compute_units), d.max_work_group, mib(d.global_mem).c_str(), mib(d.max_alloc).c_str(),
        mib(d.local_mem).c_str());
    // The variant OpenClBackend picks for this device (setKernelVariant).
    const std::string k = kernelChoice();
    const bool lanes = k == "lanes" || (k == "auto" && (d.type & CL_DEVICE_TYPE_CPU) != 0);
    std::printf("    kernels %s (%s)\n", lanes ? "lanes" : "scalar",
                k == "auto" ? "auto: by device type" : "set by --kernels / FLOWFORM_KERNELS");
  }
  if (devices.empty()) std::printf("OpenCL platforms found, but no devices.\n");
  return 0;
}
#endif

}  // namespace

std::function<int()> addDevicesCommand(CLI::App& app) {
  CLI::App* cmd =
      app.add_subcommand("devices", "List the OpenCL platforms and devices (numbers for `run --device N`)");
  addKernelsOption(cmd);
  return [] { return listDevices(); };
}

}  // namespace ff::app
