// flowform - make a liquid flow into a shape, interactively.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <map>
#include <string>

#include "app/commands.h"
#include "core/error.h"

namespace {

// `view` and `render` share the CPU with OpenGL (llvmpipe renders on the CPU
// where there is no GPU). OpenMP threads that spin-wait between phases then
// starve the renderer's threads (a 6 s script took 16 s), so these two
// commands run with OMP_WAIT_POLICY=PASSIVE unless the user chose a policy.
// The OpenMP runtime reads the variable when it loads, so the program
// restarts itself once with it set; if that fails it just goes on.
void passiveOpenMpForGraphics(int argc, char** argv) {
  if (argc < 2 || std::getenv("OMP_WAIT_POLICY")) return;
  const std::string sub = argv[1];
  if (sub != "view" && sub != "render") return;
  if (::setenv("OMP_WAIT_POLICY", "PASSIVE", 0) != 0) return;
  ::execv("/proc/self/exe", argv);
}

}  // namespace

int main(int argc, char** argv) {
  passiveOpenMpForGraphics(argc, argv);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress lines appear as they happen, also in logs
  CLI::App app{
      "flowform: SPH liquid that flows into a target shape (Yoshino & Tsuruno, shape-matching control)"};
  app.require_subcommand(0, 1);
  auto run = ff::app::addRunCommand(app);
  auto devices = ff::app::addDevicesCommand(app);
  auto view = ff::app::addViewCommand(app);
  auto render = ff::app::addRenderCommand(app);
  auto bench = ff::app::addBenchCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    for (CLI::App* sub : app.get_subcommands()) {
      if (sub->get_name() == "run") return run();
      if (sub->get_name() == "devices") return devices();
      if (sub->get_name() == "view") return view();
      if (sub->get_name() == "render") return render();
      if (sub->get_name() == "bench") return bench();
    }
    // No subcommand: run the default scene.
    return run();
  } catch (const ff::Error& e) {
    std::fprintf(stderr, "flowform: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "flowform: internal error: %s\n", e.what());
    return 2;
  }
}
