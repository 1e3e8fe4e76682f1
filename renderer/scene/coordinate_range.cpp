#include "scene/coordinate_range.h"

#include <algorithm>
#include <cstdio>

namespace kiln {

namespace {

// The matrix as Embree receives it: every entry rounded to float (an entry past float's range
// becomes infinite, which the finiteness check then refuses).
dmat4 float_rounded(const dmat4& m) {
  dmat4 out(1.0);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) out[c][r] = double(float(m[c][r]));
  return out;
}

// The largest Euclidean norm of a row of the linear part: the largest component a unit
// direction can get.
double max_row_norm(const dmat4& m) {
  double largest = 0.0;
  for (int r = 0; r < 3; ++r) largest = std::max(largest, glm::length(dvec3(m[0][r], m[1][r], m[2][r])));
  return largest;
}

double max_abs(const dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

std::string beyond(const std::string& what, double value) {
  return what + " reaches " + format_coordinate(value) + ", beyond kiln's coordinate limit of " +
         format_coordinate(max_coordinate) + " (Embree takes at most " +
         format_coordinate(embree_coordinate_limit) + ")";
}

}  // namespace

std::string format_coordinate(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

double max_abs_coordinate(const bounds3& b) {
  if (b.empty()) return 0.0;
  return std::max(max_abs(b.lower), max_abs(b.upper));
}

std::optional<std::string> transform_range_problem(const dmat4& world_from_object) {
  const dmat4 forward = float_rounded(world_from_object);
  if (!is_finite(forward)) return "the transform has an entry beyond single precision's range";
  const dmat4 inverse = glm::inverse(forward);
  // NaN compares false: a singular or overflowing inverse is refused by the same tests.
  if (!is_finite(inverse)) return std::string("the transform is not invertible in single precision");
  const double scale = max_row_norm(forward);
  if (!(scale <= max_coordinate)) return beyond("its scale (a unit direction in world space)", scale);
  const double inverse_scale = max_row_norm(inverse);
  if (!(inverse_scale <= max_coordinate))
    return beyond("its inverse scale (a unit direction in object space)", inverse_scale);
  const double translation = max_abs(dvec3(forward[3]));
  if (!(translation <= max_coordinate)) return beyond("its translation", translation);
  return std::nullopt;
}

std::optional<std::string> object_space_range_problem(const instance& inst, const bounds3& origins) {
  if (auto problem = transform_range_problem(inst.world_from_object)) return problem;
  // An affine map of a box reaches its largest components at the corners.
  const dmat4 inverse = glm::inverse(float_rounded(inst.world_from_object));
  const double reach = max_abs_coordinate(transform_bounds(inverse, origins));
  if (!(reach <= max_coordinate))
    return beyond("a ray from the camera or the scene, carried into this node's object space,", reach);
  return std::nullopt;
}

}  // namespace kiln
