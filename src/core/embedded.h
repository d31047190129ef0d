// embedded.h - text files compiled into the binary (OpenCL kernels, the
// default scene), so that the program runs from any folder.
#pragma once
#include <cstddef>
#include <string>

namespace ff {

struct EmbeddedFile {
  const char* name;  // relative path, e.g. "scenes/default.json", "kernels/density.cl"
  const char* data;
  size_t size;
};

// Null-terminated tables ({nullptr, nullptr, 0} ends them).
const EmbeddedFile* resources_files();

// Looks a file up by name in the resources table; throws ff::Error if absent.
std::string embeddedFile(const std::string& name);

}  // namespace ff
