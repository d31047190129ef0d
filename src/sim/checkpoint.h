// checkpoint.h - checkpoint files: a run saved to disk and resumed later.
//
// Layout (little-endian, as the machine writes it):
//   8 bytes  magic "FFCKPT\r\n" (a text-mode transfer or a wrong file shows)
//   u32      format version (kCheckpointVersion)
//   u32      layout: sizes of the saved structs, so a program whose Params or
//            metrics changed refuses the file instead of misreading it
//   u64      payload size in bytes
//   u64      FNV-1a 64 checksum of the payload
//   payload  the scene (scene_state.h), then Simulation::saveState().
// On the CPU backend a resumed run is bit-identical to one never interrupted.
#pragma once
#include <memory>
#include <string>

#include "sim/simulation.h"

namespace ff {

constexpr unsigned kCheckpointVersion = 8;  // 3: control radius scale; 4: the DFSPH substep; 5: the anchor;
                                            // 6: the held pressure (pressure_cfl); 7: rest-shape blend;
                                            // 8: the substeps' lead (fluid.substep_carry), and
                                            // FNV-1a's own offset basis (7 and before had
                                            // 1469598103934665603, a digit short)

// Writes the run to `path` (through a temporary file and a rename, so an
// interrupted write never leaves a half file under that name). Throws
// ff::Error naming the path.
void writeCheckpoint(const std::string& path, const Simulation& sim);

// Reads `path` and builds the run it holds on `backend`. Throws ff::Error
// naming the path: not a checkpoint, another version, a wrong checksum, a
// truncated file, or a backend that cannot resume.
std::unique_ptr<Simulation> loadCheckpoint(const std::string& path, std::unique_ptr<Backend> backend);

}  // namespace ff
