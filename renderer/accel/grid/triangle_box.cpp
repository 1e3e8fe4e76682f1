#include "accel/grid/triangle_box.h"

#include <algorithm>
#include <cmath>

namespace kiln {

namespace {

// Projects the (box-centred) triangle and the box onto axis and reports whether the intervals
// are disjoint. A zero axis (parallel edges) projects everything to 0 and separates nothing.
bool separated_on(const dvec3& axis, const dvec3& v0, const dvec3& v1, const dvec3& v2, const dvec3& half) {
  double radius = half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
  double a = glm::dot(axis, v0), b = glm::dot(axis, v1), c = glm::dot(axis, v2);
  return std::min({a, b, c}) > radius || std::max({a, b, c}) < -radius;
}

}  // namespace

bool triangle_box_overlap(const dvec3& p0, const dvec3& p1, const dvec3& p2, const bounds3& b) {
  const dvec3 centre = b.center();
  const dvec3 half = 0.5 * b.diagonal();
  const dvec3 v0 = p0 - centre, v1 = p1 - centre, v2 = p2 - centre;

  // Box face normals: the triangle's bounds against the box.
  for (int axis = 0; axis < 3; ++axis) {
    if (std::min({v0[axis], v1[axis], v2[axis]}) > half[axis]) return false;
    if (std::max({v0[axis], v1[axis], v2[axis]}) < -half[axis]) return false;
  }

  // The nine cross products of box axes and triangle edges.
  const dvec3 edges[3] = {v1 - v0, v2 - v1, v0 - v2};
  const dvec3 box_axes[3] = {dvec3(1, 0, 0), dvec3(0, 1, 0), dvec3(0, 0, 1)};
  for (const dvec3& e : edges)
    for (const dvec3& a : box_axes)
      if (separated_on(glm::cross(a, e), v0, v1, v2, half)) return false;

  // The triangle's plane: the box's extent along the normal must reach it.
  const dvec3 normal = glm::cross(edges[0], edges[1]);
  return !separated_on(normal, v0, v1, v2, half);
}

}  // namespace kiln
