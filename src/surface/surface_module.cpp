// surface_module.cpp - finds and loads the surface module once (dlopen).
#include "surface/surface_module.h"

#include <dlfcn.h>
#include <limits.h>
#include <stdlib.h>

#include <mutex>
#include <string>
#include <vector>

#include "core/error.h"

namespace ff {
namespace {

std::string folderOf(const std::string& path) {
  const size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

// Where to look: the running program's folder, the folder of the object
// that holds this code, the build folder.
std::vector<std::string> moduleFolders() {
  std::vector<std::string> out;
  char exe[PATH_MAX];
  if (realpath("/proc/self/exe", exe)) out.push_back(folderOf(exe));
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&callSurfaceModule), &info) && info.dli_fname) {
    char real[PATH_MAX];
    if (realpath(info.dli_fname, real)) out.push_back(folderOf(real));
  }
#ifdef FF_SURFACE_MODULE_DIR
  out.push_back(FF_SURFACE_MODULE_DIR);
#endif
  return out;
}

FfSurfaceModuleFn loadModule() {
  std::string tried;
  for (const std::string& folder : moduleFolders()) {
    const std::string path = folder + "/" + kSurfaceModuleName;
    void* lib = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
      const char* why = dlerror();
      tried += "\n  " + path + ": " + (why ? why : "not loaded");
      continue;
    }
    if (void* fn = dlsym(lib, "ff_surface_module_v1")) return reinterpret_cast<FfSurfaceModuleFn>(fn);
    tried += "\n  " + path + ": no ff_surface_module_v1 in it";
    dlclose(lib);
  }
  throw Error(std::string("surface: cannot load the surface module ") + kSurfaceModuleName +
              " (it is built beside build/flowform); tried:" + tried);
}

}  // namespace

SurfaceMesh callSurfaceModule(const FfSurfaceCall& call) {
  static std::mutex mutex;
  static FfSurfaceModuleFn fn = nullptr;
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (!fn) fn = loadModule();  // a failure is retried (and reported) next time
  }
  SurfaceMesh mesh;
  char error[1024] = {0};
  if (fn(&call, &mesh, error, sizeof error) != 0) throw Error(error);
  return mesh;
}

}  // namespace ff
