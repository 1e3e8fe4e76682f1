// Core math for kiln: GLM vector and matrix aliases plus the few helpers every module shares.
// Depends on GLM only. Transforms are double precision (placement of far-away geometry must not
// lose bits); per-vertex data and rays are float, as Embree consumes them.
#pragma once

#include <cmath>
#include <glm/glm.hpp>
#include <limits>

namespace kiln {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using dvec3 = glm::dvec3;
using dvec4 = glm::dvec4;
using mat3 = glm::mat3;
using dmat3 = glm::dmat3;
using dmat4 = glm::dmat4;

constexpr float pi = 3.14159265358979323846f;
constexpr float inf = std::numeric_limits<float>::infinity();

// True when every component is a finite number (no NaN, no infinity).
template <int N, typename T, glm::qualifier Q>
bool is_finite(const glm::vec<N, T, Q>& v) {
  for (int i = 0; i < N; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// True when every entry of the matrix is finite.
inline bool is_finite(const dmat4& m) {
  for (int c = 0; c < 4; ++c)
    if (!is_finite(m[c])) return false;
  return true;
}

// Applies an affine transform to a point.
inline dvec3 transform_point(const dmat4& m, const dvec3& p) { return dvec3(m * dvec4(p, 1.0)); }

// Applies the linear part of an affine transform to a direction.
inline dvec3 transform_vector(const dmat4& m, const dvec3& v) { return dmat3(m) * v; }

// The matrix that maps object-space normals to world space: the inverse transpose of the linear
// part. It keeps the front face defined by object-space winding even under mirroring transforms.
inline dmat3 normal_matrix(const dmat4& world_from_object) {
  return glm::transpose(glm::inverse(dmat3(world_from_object)));
}

// Axis-aligned bounding box in world or object space.
struct bounds3 {
  dvec3 lower{std::numeric_limits<double>::infinity()};
  dvec3 upper{-std::numeric_limits<double>::infinity()};

  bool empty() const { return lower.x > upper.x || lower.y > upper.y || lower.z > upper.z; }
  void extend(const dvec3& p) {
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
  }
  void extend(const bounds3& b) {
    lower = glm::min(lower, b.lower);
    upper = glm::max(upper, b.upper);
  }
  dvec3 center() const { return 0.5 * (lower + upper); }
  dvec3 diagonal() const { return upper - lower; }
};

// The bounds of an object-space box after an affine transform (all eight corners).
inline bounds3 transform_bounds(const dmat4& m, const bounds3& b) {
  bounds3 result;
  if (b.empty()) return result;
  for (int i = 0; i < 8; ++i) {
    dvec3 corner((i & 1) ? b.upper.x : b.lower.x, (i & 2) ? b.upper.y : b.lower.y,
                 (i & 4) ? b.upper.z : b.lower.z);
    result.extend(transform_point(m, corner));
  }
  return result;
}

// Builds an orthonormal basis (t, b) around the unit vector n (Duff et al. 2017).
inline void orthonormal_basis(const vec3& n, vec3& t, vec3& b) {
  float sign = std::copysign(1.0f, n.z);
  float a = -1.0f / (sign + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = vec3(c, sign + n.y * n.y * a, -n.y);
}

inline float luminance(const vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

}  // namespace kiln
