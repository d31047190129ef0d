// text_file.h - reads a whole text file the user named (a scene, a script).
#pragma once
#include <string>

namespace ff {

// The largest scene or script file read (they are small JSON files; the
// largest in scenes/ is a few KiB).
constexpr size_t kMaxTextFileBytes = size_t(16) << 20;

// The file's contents. Throws ff::Error "PATH: cannot open WHAT file (reason)"
// when it is missing, unreadable or a folder, and "PATH: the WHAT file is
// larger than 16 MiB" when it (or a device or pipe it names) gives more.
std::string readTextFile(const std::string& path, const std::string& what);

}  // namespace ff
