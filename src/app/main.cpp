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
#include "core/resource_limits.h"

namespace {

// Every command that simulates runs with OMP_WAIT_POLICY=PASSIVE unless the
// user chose a policy:
// - `view` and `render` share the CPU with OpenGL (llvmpipe renders on the CPU
//   where there is no GPU); threads that spin-wait between phases starve the
//   renderer's threads (a 6 s script took 16 s).
// - `run` and `bench`: on a quiet machine the policies are equally fast; on a
//   loaded one (a second busy process) the passive wait is 25-35 % faster
//   (docs/PERFORMANCE.md, "OpenMP wait policy").
// `run` and `bench` first spin briefly (libgomp: GOMP_SPINCOUNT=1000, unless
// set): a DFSPH step is some 30 short parallel loops per substep, and a
// thread that sleeps between them at once costs a wake-up each time (the
// peer dam break took 25 % less wall time on a quiet machine, 4 % more on a
// loaded one; docs/PERFORMANCE.md, "OpenMP wait policy").
// The OpenMP runtime reads the variables when it loads, so the program
// restarts itself once with them set; if that fails it just goes on.
// Not where the user binds threads to places (OMP_PROC_BIND, OMP_PLACES,
// GOMP_CPU_AFFINITY): libgomp binds the first thread to the first place as it
// loads, and the restarted program inherits that one CPU, so every thread ran
// there (the peer dam break with 2 threads took as long as with 1,
// docs/PERFORMANCE.md, "OpenMP wait policy").
void passiveOpenMp(int argc, char** argv) {
  if (argc < 2 || std::getenv("OMP_WAIT_POLICY")) return;
  for (const char* bind : {"OMP_PROC_BIND", "OMP_PLACES", "GOMP_CPU_AFFINITY"})
    if (std::getenv(bind)) return;
  const std::string sub = argv[1];
  if (sub != "view" && sub != "render" && sub != "run" && sub != "bench") return;
  if (::setenv("OMP_WAIT_POLICY", "PASSIVE", 0) != 0) return;
  if ((sub == "run" || sub == "bench") && ::setenv("GOMP_SPINCOUNT", "1000", 0) != 0) return;
  ::execv("/proc/self/exe", argv);
}

bool isCommand(const CLI::App& app, const std::string& name) {
  for (const CLI::App* sub : app.get_subcommands({}))
    if (sub->check_name(name)) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  passiveOpenMp(argc, argv);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress lines appear as they happen, also in logs
  CLI::App app{
      "flowform: SPH liquid that flows into a target shape (Yoshino & Tsuruno, shape-matching control)"};
  app.name("flowform");  // the usage reads "flowform run ...", not the path it was started by
  app.require_subcommand(0, 1);
  std::string max_memory;
  app.add_option("--max-memory", max_memory,
                 "The most memory a run may plan to use, e.g. 4G or 512M (default: half of the machine's "
                 "memory, or of the process's memory limit)");
  app.fallthrough();  // --max-memory may also follow the subcommand
  auto run = ff::app::addRunCommand(app);
  auto devices = ff::app::addDevicesCommand(app);
  auto view = ff::app::addViewCommand(app);
  auto render = ff::app::addRenderCommand(app);
  auto bench = ff::app::addBenchCommand(app);
  // A bare `flowform` shows what it can do.
  if (argc < 2) {
    std::printf("%s", app.help().c_str());
    return 0;
  }
  // A word that is not a command: one line, exit code 2 (a usage error).
  const std::string first = argv[1];
  if (!first.empty() && first[0] != '-' && !isCommand(app, first)) {
    std::fprintf(
        stderr,
        "flowform: unknown command '%s' (commands: run, devices, view, render, bench; see flowform --help)\n",
        first.c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help prints the help and exits 0; every other usage error exits 2.
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    if (!max_memory.empty())
      ff::setMemoryLimit(ff::parseByteSize(max_memory, "--max-memory"), "--max-memory");
    for (CLI::App* sub : app.get_subcommands()) {
      if (sub->get_name() == "run") return run();
      if (sub->get_name() == "devices") return devices();
      if (sub->get_name() == "view") return view();
      if (sub->get_name() == "render") return render();
      if (sub->get_name() == "bench") return bench();
    }
    // Only options (e.g. --help handled above): show the usage.
    std::printf("%s", app.help().c_str());
    return 0;
  } catch (const ff::Error& e) {
    std::fprintf(stderr, "flowform: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "flowform: internal error: %s\n", e.what());
    return 2;
  }
}
