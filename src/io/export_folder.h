// export_folder.h - the export folder's policy towards frames already in it.
//
// A folder that already holds files of flowform's frame naming (another
// run's frames) is refused, so that two runs never leave a mix; with
// `overwrite` exactly those files are removed first. Files of any other name
// are never touched. Frame naming: PREFIX_NNNNN.EXT (PREFIX fluid, control or
// surface; NNNNN one or more digits; EXT one of vtu bgeo ply obj vdb pcache),
// the indexes fluid.pvd, control.pvd, surface.pvd, and their .tmp files.
#pragma once
#include <string>
#include <vector>

namespace ff {

// True for a file name (no folder) of flowform's frame naming.
bool isFrameFileName(const std::string& name);

// Creates `dir` if needed. If it holds frame files: with overwrite, removes
// them; else throws ff::Error naming the folder, one of the files and the
// way out, `overwrite_option` (the CLI's --overwrite, Python's
// overwrite=True). Throws ff::Error naming the folder if it cannot be
// created, read or cleaned.
void prepareExportFolder(const std::string& dir, bool overwrite,
                         const std::string& overwrite_option = "--overwrite");

}  // namespace ff
