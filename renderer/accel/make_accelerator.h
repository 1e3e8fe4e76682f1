// Picks a traversal backend by name for the CLI: Embree, the uniform grid or the adaptive grid.
// The only place that knows every backend; shading and rendering see the accelerator interface.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "accel/accelerator.h"
#include "accel/embree/embree_options.h"
#include "accel/grid/grid.h"
#include "scene/scene.h"

namespace kiln {

enum class accel_kind { embree, grid, adaptive_grid };

// "embree", "grid", "adaptive-grid": the spelling of the --accel option.
const char* accel_kind_name(accel_kind kind);
std::optional<accel_kind> parse_accel_kind(const std::string& name);

// Builds the backend over s (which must outlive it). grid holds the grid settings of the
// command line (--grid-*): the adaptive grid uses them as they are; the uniform grid uses the same
// density and resolution without subdivision (max_depth 0); Embree ignores them. embree holds the
// BVH build settings (--bvh-quality, --bvh-compact), which the grids ignore.
// Throws kiln::error (render) on failure.
std::unique_ptr<accelerator> make_accelerator(const scene& s, accel_kind kind,
                                              const grid_options& grid = adaptive_grid_options(),
                                              const embree_options& embree = {});

// The grid options a backend of this kind is built with from the command line's settings.
grid_options grid_options_for(accel_kind kind, const grid_options& grid);

// Sizes of a grid backend's structure; nothing for Embree (whose internals are opaque).
std::optional<grid_statistics> accelerator_grid_statistics(const accelerator& accel);

}  // namespace kiln
