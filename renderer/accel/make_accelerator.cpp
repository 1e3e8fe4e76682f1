#include "accel/make_accelerator.h"

#include "accel/embree/embree_accelerator.h"
#include "accel/grid/grid_accelerator.h"

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

std::unique_ptr<accelerator> make_accelerator(const scene& s, accel_kind kind) {
  switch (kind) {
    case accel_kind::embree:
      return std::make_unique<embree_accelerator>(s);
    case accel_kind::grid:
      return std::make_unique<grid_accelerator>(s, uniform_grid_options());
    case accel_kind::adaptive_grid:
      return std::make_unique<grid_accelerator>(s, adaptive_grid_options());
  }
  return std::make_unique<embree_accelerator>(s);
}

}  // namespace kiln
