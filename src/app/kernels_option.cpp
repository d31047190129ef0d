#include "app/kernels_option.h"

#include <string>

#include "host/backend_factory.h"

namespace ff::app {

void addKernelsOption(CLI::App* cmd) {
  cmd->add_option_function<std::string>(
         "--kernels", [](const std::string& k) { setKernelChoice(k); },
         "OpenCL kernels: auto (by device type, the default), scalar (one particle per work-item, for GPUs) "
         "or lanes (8 particles per work-item, for CPU devices); default $FLOWFORM_KERNELS")
      ->check(CLI::IsMember({"auto", "scalar", "lanes"}));
}

}  // namespace ff::app
