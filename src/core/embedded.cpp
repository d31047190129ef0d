#include "core/embedded.h"

#include <cstring>

#include "core/error.h"

namespace ff {

std::string embeddedFile(const std::string& name) {
  for (const EmbeddedFile* f = resources_files(); f->name; ++f)
    if (name == f->name) return std::string(f->data, f->size);
  throw Error("internal: embedded file '" + name + "' is missing from the build");
}

}  // namespace ff
