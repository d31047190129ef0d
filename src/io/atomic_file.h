// atomic_file.h - a file written whole or not at all: the bytes go to
// PATH.tmp, which is then renamed to PATH, so a failed or interrupted write
// never leaves a half-written PATH (nor, on failure, the .tmp).
#pragma once
#include <initializer_list>
#include <string>
#include <string_view>

namespace ff {

// Writes the parts one after the other. `kind` names the file in messages
// ("VTU file"). Throws ff::Error naming the path and the system's reason.
void writeFileAtomically(const std::string& path, const char* kind,
                         std::initializer_list<std::string_view> parts);

}  // namespace ff
