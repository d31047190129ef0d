// scene_geometry.h - the CPU-side geometry the renderer uploads: container
// walls and edges, the floor, the region wireframe, the ghost's surface faces
// and the particles as instance data. Pure functions of the frame.
#pragma once
#include <vector>

#include "render/frame_data.h"

namespace ff::render {

// Line segments, 6 floats (two xyz end points) each.
std::vector<float> boxEdges(const Vec3& lo, const Vec3& hi);
// Three great circles (in the xy, yz and zx planes) of `segments` segments each.
std::vector<float> sphereWireframe(const Vec3& centre, float radius, int segments);
// The region's outline: its box or sphere; nothing for the whole fluid.
std::vector<float> regionWireframe(const RegionDesc& region);

// Triangles with normals, 6 floats (xyz, normal) per vertex.
// A square floor at the container's bottom, `half_extent` around its centre.
std::vector<float> floorQuad(const ContainerDesc& c, float half_extent);
// The container's four side walls, normals pointing out.
std::vector<float> containerWalls(const ContainerDesc& c);

// The pixel rectangle (x, y from the bottom left, w, h) that holds every
// instance's projected sphere of `radius` plus `margin` pixels, clipped to
// the viewport; the whole viewport when an instance is (nearly) behind the
// eye. `nearest` is the smallest eye depth of an instance centre (0 when
// the whole viewport is returned).
struct PixelRect {
  int x = 0, y = 0, w = 0, h = 0;
  float nearest = 0.0f;
};
PixelRect projectedBounds(const std::vector<float>& instances, const Eigen::Matrix4f& view_proj, float radius,
                          int width, int height, int margin);

// A checker square size for a container: about an eighth of its largest
// extent, rounded to 1, 2 or 5 times a power of ten.
float floorTile(const ContainerDesc& c);

// Instances of 4 floats: fluid particles (xyz, 0), control particles (xyz,
// s_i), ghost faces (voxel centre xyz, face 0..5; only faces on the surface
// when frame.ghost_faces is given).
std::vector<float> fluidInstances(const FrameData& f);
std::vector<float> controlInstances(const FrameData& f);
std::vector<float> ghostFaceInstances(const FrameData& f);

}  // namespace ff::render
