// mesh_file_checks.h - structural checks of a mesh file before assimp reads
// it. assimp 5.2 (Debian 12) trusts PLY and OFF files: a garbled header or a
// list length that runs past the end makes it allocate billions of elements,
// loop for minutes, read out of bounds or abort (found by fuzzing); these
// checks turn such files into ff::Errors.
#pragma once
#include <cstdint>
#include <string>

namespace ff {

// Throws ff::Error "PATH: problem" for a PLY file whose header does not follow
// the PLY grammar or whose data does not match its header (too short, a list
// length past the end, a value that is not a number), or an OFF file whose
// counts exceed the file size. Other files pass (assimp checks them itself).
void checkMeshFileStructure(const std::string& path, uintmax_t file_size);

}  // namespace ff
