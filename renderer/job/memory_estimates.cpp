#include "job/memory_estimates.h"

namespace kiln {

namespace {

// 100 copies of a 100k-triangle mesh, each its own BVH, peaked at 959 MB: ~94 bytes a triangle
// with the mesh's own arrays; Embree's low quality adds about 30% to the BVH.
constexpr uint64_t bytes_per_triangle = 128;
// An instance: Embree's instance geometry and its top-level BVH leaf, the scene's own record.
constexpr uint64_t bytes_per_instance = 512;

}  // namespace

uint64_t accelerator_bytes(const scene& world) {
  uint64_t triangles = 0;
  for (const mesh& m : world.meshes) triangles += m.indices.size() / 3;
  return triangles * bytes_per_triangle + uint64_t(world.instances.size()) * bytes_per_instance;
}

uint64_t film_and_output_bytes(const pixel_rect& region, const aov_set& aovs, int light_groups) {
  // The writer converts every layer to the file's layout at once: at most the film's size again.
  return 2 * film_bytes(region.width(), region.height(), aovs, light_groups);
}

}  // namespace kiln
