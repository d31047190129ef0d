// text_file.h - reads a whole text file the user named (a scene, a script).
#pragma once
#include <string>

namespace ff {

// The file's contents. Throws ff::Error "PATH: cannot open WHAT file (reason)"
// when it is missing, unreadable or a folder.
std::string readTextFile(const std::string& path, const std::string& what);

}  // namespace ff
