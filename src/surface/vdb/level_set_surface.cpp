// level_set_surface.cpp - the surface module (libflowform_surface.so, why a
// module: surface/surface_module.h): OpenVDB's particles -> level set ->
// triangles.
#include <omp.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/ValueTransformer.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>

#include "core/error.h"
#include "surface/surface_module.h"

namespace ff {
namespace {

// The particle list ParticlesToLevelSet reads.
struct Particles {
  using PosType = openvdb::Vec3R;
  size_t n;
  const float *x, *y, *z;
  size_t size() const { return n; }
  void getPos(size_t i, openvdb::Vec3R& p) const { p = openvdb::Vec3R(x[i], y[i], z[i]); }
};

// The mean height, over a flat face of a square lattice of spacing 1, of the
// union of spheres of radius r (>= 0.75, so that the union covers the face)
// centred on the lattice points: the bumps of the union lower its mean below r.
double latticeFaceHeight(double r) {
  const int m = 48;
  double sum = 0.0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const double x = (i + 0.5) / m, y = (j + 0.5) / m;
      double best = 0.0;
      for (int a = -4; a <= 5; ++a)
        for (int b = -4; b <= 5; ++b) {
          const double d2 = (x - a) * (x - a) + (y - b) * (y - b);
          if (d2 < r * r) best = std::max(best, std::sqrt(r * r - d2));
        }
      sum += best;
    }
  return sum / (m * m);
}

void initVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

SurfaceMesh levelSetSurface(size_t n, const float* x, const float* y, const float* z, float spacing,
                            const SurfaceOptions& o, const std::string& vdb_path, double time) {
  initVdb();
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                              size_t(std::max(1, omp_get_max_threads())));
  const double voxel = double(o.voxel) * spacing;
  const double radius = double(o.radius) * spacing;
  // Erode the union of spheres so that a flat face of the rest lattice lies,
  // on average, half a spacing beyond the outer centres (where the volume of
  // the outer particles ends).
  const double erosion = (latticeFaceHeight(o.radius) - 0.5) * spacing;
  // The narrow band must hold the erosion and the smoothing's stencil.
  const float half_width = float(std::max(3.0, std::ceil(erosion / voxel) + 3.0));
  openvdb::FloatGrid::Ptr grid = openvdb::createLevelSet<openvdb::FloatGrid>(voxel, half_width);
  grid->setName("surface");
  grid->insertMeta("time", openvdb::DoubleMetadata(time));
  SurfaceMesh mesh;
  if (n > 0) {
    openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*grid);
    raster.rasterizeSpheres(Particles{n, x, y, z}, radius);
    raster.finalize(true);
    // The erosion: every distance grows by it (a shift of the values is exact
    // for the distances of the narrow band, and costs one pass).
    const float shift = float(erosion);
    openvdb::tools::foreach (grid->beginValueAll(), [shift](const openvdb::FloatGrid::ValueAllIter& it) {
      it.setValue(*it + shift);
    });
    if (o.smoothing > 0) {
      openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*grid);
      // First-order renormalisation: the smoothing moves the surface by a
      // fraction of a voxel per iteration, the default fifth-order scheme
      // costs several times as much for no visible difference.
      filter.setSpatialScheme(openvdb::math::FIRST_BIAS);
      filter.setTemporalScheme(openvdb::math::TVD_RK1);
      filter.setNormCount(1);
      for (int i = 0; i < o.smoothing; ++i) filter.meanCurvature();
    }

    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(*grid, points, tris, quads, 0.0, 0.0);
    mesh.vertices.reserve(points.size());
    for (const openvdb::Vec3s& p : points) mesh.vertices.push_back({p.x(), p.y(), p.z()});
    mesh.triangles.reserve(tris.size() + 2 * quads.size());
    for (const openvdb::Vec3I& t : tris) mesh.triangles.push_back({t[0], t[1], t[2]});
    for (const openvdb::Vec4I& q : quads) {
      mesh.triangles.push_back({q[0], q[1], q[2]});
      mesh.triangles.push_back({q[0], q[2], q[3]});
    }
    // Wind outwards (a positive enclosed volume).
    if (mesh.volume() < 0.0)
      for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  }
  if (!vdb_path.empty()) {
    const std::string tmp = vdb_path + ".tmp";
    try {
      openvdb::io::File file(tmp);
      file.write({grid});
      file.close();
    } catch (const openvdb::Exception& e) {
      std::remove(tmp.c_str());
      throw Error(vdb_path + ": cannot write the VDB file (" + e.what() + ")");
    }
    if (std::rename(tmp.c_str(), vdb_path.c_str()) != 0) {
      std::remove(tmp.c_str());
      throw Error(vdb_path + ": cannot rename the VDB file into place");
    }
  }
  return mesh;
}

}  // namespace
}  // namespace ff

// The module's one entry (surface/surface_module.h). Every exception stays
// inside: its message goes back in `error`.
extern "C" __attribute__((visibility("default"))) int ff_surface_module_v1(const FfSurfaceCall* call,
                                                                           ff::SurfaceMesh* out, char* error,
                                                                           size_t error_size) {
  try {
    *out = ff::levelSetSurface(call->n, call->x, call->y, call->z, call->spacing, *call->options,
                               call->vdb_path, call->time);
    return 0;
  } catch (const std::exception& e) {
    std::snprintf(error, error_size, "%s", e.what());
  } catch (...) {
    std::snprintf(error, error_size, "surface: an unknown error in the surface module");
  }
  return 1;
}
