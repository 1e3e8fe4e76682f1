// What a job's render stage will allocate, estimated before it does: the backend's acceleration
// structure, the texture mip pyramids and the film with its AOVs. The job charges them to its
// memory budget (core/memory_budget.h) after the scene has loaded and before each is built.
#pragma once

#include <cstdint>

#include "render/film.h"
#include "scene/scene.h"

namespace kiln {

// Bytes of a backend over world: per triangle and per instance, rough upper bounds measured with
// Embree's BVH at --bvh-quality low (its largest: ~30% over medium) and the grids.
uint64_t accelerator_bytes(const scene& world);

// Bytes of the film over region with aovs, the renderer's per-thread accumulation aside, and the
// EXR writer's copy of it in the file's layout.
uint64_t film_and_output_bytes(const pixel_rect& region, const aov_set& aovs, int light_groups = 0);

}  // namespace kiln
