// surface_options.h - how the liquid's surface mesh is made from the fluid
// particles (surface/particle_surface.h) and in which file format it goes.
#pragma once

namespace ff {

enum class SurfaceMeshFormat { Obj, Ply };

struct SurfaceOptions {
  bool enabled = false;
  // Each particle is a sphere of this radius, in rest spacings (the cube root
  // of a particle's rest volume); the union is then eroded so that a flat
  // face of resting fluid lies (on average) half a spacing beyond the outer
  // particles' centres, where the fluid's volume ends. >= 0.75 closes the gaps of a
  // rest lattice.
  float radius = 1.0f;
  float voxel = 0.4f;  // level-set voxel size, in rest spacings
  int smoothing = 1;   // mean-curvature flow iterations on the level set
  SurfaceMeshFormat format = SurfaceMeshFormat::Obj;
  bool vdb = false;  // also write the level set as a .vdb file
};

}  // namespace ff
