// ply_writer.h - particle snapshots as binary little-endian PLY point clouds:
// vertex properties `float x y z`, then one property per attribute component
// (float or int), and the simulated time in a `comment time SECONDS` line.
// Written atomically (io/atomic_file.h); errors throw ff::Error naming the path.
#pragma once
#include <string>

#include "io/point_cloud.h"

namespace ff {

// A 3-component attribute NAME becomes the properties NAME_x NAME_y NAME_z.
void writePly(const std::string& path, const PointCloud& cloud);

}  // namespace ff
