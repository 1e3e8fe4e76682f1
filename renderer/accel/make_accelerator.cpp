#include "accel/make_accelerator.h"

#include "accel/embree/embree_accelerator.h"
#include "accel/grid/grid_accelerator.h"
#include "core/error.h"

namespace kiln {

const char* accel_kind_name(accel_kind kind) {
  switch (kind) {
    case accel_kind::embree:
      return "embree";
    case accel_kind::grid:
      return "grid";
    case accel_kind::adaptive_grid:
      return "adaptive-grid";
  }
  return "embree";
}

std::optional<accel_kind> parse_accel_kind(const std::string& name) {
  for (accel_kind k : {accel_kind::embree, accel_kind::grid, accel_kind::adaptive_grid})
    if (name == accel_kind_name(k)) return k;
  return std::nullopt;
}

grid_options grid_options_for(accel_kind kind, const grid_options& grid) {
  grid_options o = grid;
  if (kind == accel_kind::grid) o.max_depth = 0;
  return o;
}

std::unique_ptr<accelerator> make_accelerator(const scene& s, accel_kind kind, const grid_options& grid,
                                              const embree_options& embree) {
  if (kind == accel_kind::embree) return std::make_unique<embree_accelerator>(s, embree);
  // The grids hold one placement per instance; time steps are Embree's (motion blur).
  if (s.shutter.any())
    throw input_error("", "--accel",
                      std::string("motion blur (--shutter) of a moving scene needs --accel embree: the ") +
                          accel_kind_name(kind) + " backend traces the scene at one time");
  return std::make_unique<grid_accelerator>(s, grid_options_for(kind, grid));
}

std::optional<grid_statistics> accelerator_grid_statistics(const accelerator& accel) {
  if (const auto* g = dynamic_cast<const grid_accelerator*>(&accel)) return g->statistics();
  return std::nullopt;
}

}  // namespace kiln
