#include "shade/shading_normal.h"

#include <algorithm>
#include <cmath>

namespace kiln {

vec3 bend_toward_viewer(const vec3& ng, const vec3& to_viewer, const vec3& n) {
  const float b = glm::dot(to_viewer, ng);  // the viewer's height above the geometric plane
  if (!(b > 0.0f)) return n;
  const float threshold = std::min(0.9f * b, 0.01f);
  const vec3 mirrored = 2.0f * glm::dot(n, to_viewer) * n - to_viewer;
  if (glm::dot(mirrored, ng) >= threshold) return n;

  // In the plane of ng and x (n's part across ng), n' = sin φ·x + cos φ·ng mirrors to_viewer to a
  // height a·sin 2φ + b·cos 2φ = r·cos(2φ − β) with a = to_viewer·x, r = hypot(a, b), β = atan2(a, b).
  // At φ = 0 (n' = ng) the height is b > threshold; the first φ > 0 where it falls to the threshold
  // is 2φ = β + acos(threshold / r), which lies between ng and n because n is below the threshold.
  const vec3 across = n - glm::dot(n, ng) * ng;
  const double across_length = glm::length(dvec3(across));
  if (!(across_length > 0.0)) return ng;
  const dvec3 x = dvec3(across) / across_length;
  const double a = glm::dot(dvec3(to_viewer), x);
  const double r = std::hypot(a, double(b));
  const double phi = 0.5 * (std::atan2(a, double(b)) + std::acos(std::min(double(threshold) / r, 1.0)));
  return vec3(glm::normalize(std::sin(phi) * x + std::cos(phi) * dvec3(ng)));
}

}  // namespace kiln
