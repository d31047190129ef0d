// flowform - make a liquid flow into a shape, interactively.
#include <cstdio>
#include <exception>
#include <functional>
#include <map>

#include "app/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
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
