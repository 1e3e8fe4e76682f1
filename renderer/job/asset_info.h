// What an asset holds and what rendering it would cost, for `kiln info` and kiln.info(): the file's
// declarations (io/gltf/gltf_summary.h), the scene as a render loads it (its cameras in --camera's
// order, geometry per node, bounds, lighting) and the batch plan's estimate of the render the
// options describe. Loads as run_job does, so bad input fails with the same errors.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/gltf/gltf_summary.h"
#include "job/plan_estimate.h"
#include "job/render_options.h"
#include "scene/scene.h"

namespace kiln {

// The geometry one node places (EXT_mesh_gpu_instancing's copies counted each).
struct node_geometry {
  uint64_t triangles = 0;
  uint64_t quadrics = 0;
};

struct asset_info {
  std::string file;
  gltf_summary declared;
  int scene_index = -1;                 // the scene a render shows; -1: the file has none
  std::vector<camera> cameras;          // as placed, in the order --camera's index counts them
  std::vector<node_geometry> geometry;  // per glTF node
  uint64_t triangles = 0, quadrics = 0, instances = 0, meshes = 0;
  bounds3 bounds;             // world space, every instance; empty when nothing is placed
  std::string view;           // the render's camera ("camera 'Camera001'", "default view", ...)
  std::string lighting;       // what lights it ("file lights (5)", "studio environment", ...)
  int width = 0, height = 0;  // the render's image size
  int samples_per_pixel = 0;
  plan_estimate estimate;
};

// Loads options.input as a render with options would (warn hears the loader's warnings and notes)
// and estimates that render. Throws kiln::error as run_job does.
asset_info describe_asset(const render_options& options, const std::atomic<bool>* cancel = nullptr,
                          const std::function<void(const std::string&)>& warn = {});

// The same for a scene loaded and prepared already (job/loaded_scene.h), whose file declares declared.
struct prepared_scene;
asset_info describe_prepared(const render_options& options, const prepared_scene& prepared,
                             gltf_summary declared);

// The info as one JSON document (keys documented in docs/info.md), indented by 2.
std::string asset_info_json(const asset_info& info);

}  // namespace kiln
