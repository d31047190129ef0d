// bgeo_writer.h - particle snapshots in Houdini's classic binary geometry
// format (.bgeo, version 5: the binary form of the documented PGEOMETRY V5
// .geo layout, the variant partio and SPlisHSPlasH write and Houdini reads).
// Points only (no primitives): P, then every attribute as a point attribute
// (float, int or vector), and the simulated time as the detail attribute
// `time`. Written atomically; errors throw ff::Error naming the path.
//
// Layout, all numbers big-endian:
//   "Bgeo" 'V' int32 version=5
//   int32 nPoints nPrims=0 nPointGroups=0 nPrimGroups=0
//   int32 nPointAttrib nVertexAttrib=0 nPrimAttrib=0 nAttrib=1
//   per point attribute: uint16 name length, name, uint16 size,
//     int32 type (0 float, 1 int, 5 vector), `size` 32-bit default values
//   per point: float x y z w(=1), then each attribute's `size` 32-bit values
//   per detail attribute: its definition as above, then its values
//   the end: bytes 0x00 0xff
#pragma once
#include <string>

#include "io/point_cloud.h"

namespace ff {

void writeBgeo(const std::string& path, const PointCloud& cloud);

}  // namespace ff
