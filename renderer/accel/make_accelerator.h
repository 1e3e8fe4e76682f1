// Picks a traversal backend by name for the CLI: Embree, the uniform grid or the adaptive grid.
// The only place that knows every backend; shading and rendering see the accelerator interface.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "accel/accelerator.h"
#include "scene/scene.h"

namespace kiln {

enum class accel_kind { embree, grid, adaptive_grid };

// "embree", "grid", "adaptive-grid": the spelling of the --accel option.
const char* accel_kind_name(accel_kind kind);
std::optional<accel_kind> parse_accel_kind(const std::string& name);

// Builds the backend over s (which must outlive it). Throws kiln::error (render) on failure.
std::unique_ptr<accelerator> make_accelerator(const scene& s, accel_kind kind);

}  // namespace kiln
