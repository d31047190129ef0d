// mesh_file_checks.h - cheap checks of a mesh file's header before assimp
// reads it. assimp 5.2 trusts PLY and OFF headers: a garbled one makes it
// allocate billions of elements, loop for minutes, or crash (found by fuzzing
// the Debian 12 build); these checks turn such files into ff::Errors.
#pragma once
#include <cstdint>
#include <string>

namespace ff {

// Throws ff::Error "PATH: problem" when the file is a PLY file whose header
// does not follow the PLY grammar or declares more data than the file holds,
// or an OFF file whose counts exceed the file size. Other files pass.
void checkMeshFileHeader(const std::string& path, uintmax_t file_size);

}  // namespace ff
