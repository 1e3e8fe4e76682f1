#include "io/gltf/mesh_tangents.h"

#include <cmath>

namespace kiln {

namespace {

// Any unit vector perpendicular to n (for vertices without a UV derivative).
vec3 any_perpendicular(const vec3& n) {
  vec3 axis = std::abs(n.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0);
  return glm::normalize(glm::cross(axis, n));
}

// The mesh's normals, or for a flat-shaded mesh (no normals) the area-weighted mean of the
// face normals around each vertex: shading projects the interpolated tangent onto each face's
// own plane, so this is exact wherever a vertex's faces are coplanar.
std::vector<dvec3> vertex_normals(const mesh& m) {
  std::vector<dvec3> normals(m.positions.size(), dvec3(0.0));
  if (!m.normals.empty()) {
    for (size_t i = 0; i < normals.size(); ++i) normals[i] = dvec3(m.normals[i]);
    return normals;
  }
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const uint32_t i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
    const dvec3 p0(m.positions[i0]);
    const dvec3 face = glm::cross(dvec3(m.positions[i1]) - p0, dvec3(m.positions[i2]) - p0);
    for (uint32_t i : {i0, i1, i2}) normals[i] += face;
  }
  for (dvec3& normal : normals) {
    const double len = glm::length(normal);
    normal = len > 0.0 && std::isfinite(len) ? normal / len : dvec3(0, 0, 1);
  }
  return normals;
}

}  // namespace

std::vector<vec4> generate_tangents(const mesh& m, const std::vector<vec2>& uv) {
  const size_t n = m.positions.size();
  std::vector<dvec3> du(n, dvec3(0.0)), dv(n, dvec3(0.0));
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const uint32_t i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
    const dvec3 e1 = dvec3(m.positions[i1]) - dvec3(m.positions[i0]);
    const dvec3 e2 = dvec3(m.positions[i2]) - dvec3(m.positions[i0]);
    const glm::dvec2 w1 = glm::dvec2(uv[i1]) - glm::dvec2(uv[i0]);
    const glm::dvec2 w2 = glm::dvec2(uv[i2]) - glm::dvec2(uv[i0]);
    const double det = w1.x * w2.y - w2.x * w1.y;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) continue;
    // dP/du and dP/dv of the triangle; dividing by |det| instead of det would lose mirroring.
    // Weighted by the triangle's area (the cross product's length), as the sum of unnormalised
    // per-triangle frames is.
    const double area = glm::length(glm::cross(e1, e2));
    const dvec3 t_u = (e1 * w2.y - e2 * w1.y) / det;
    const dvec3 t_v = (e2 * w1.x - e1 * w2.x) / det;
    const double lu = glm::length(t_u), lv = glm::length(t_v);
    if (!(lu > 0.0) || !(lv > 0.0) || !std::isfinite(lu) || !std::isfinite(lv)) continue;
    for (uint32_t i : {i0, i1, i2}) {
      du[i] += t_u / lu * area;
      dv[i] += t_v / lv * area;
    }
  }
  const std::vector<dvec3> normals = vertex_normals(m);
  std::vector<vec4> tangents(n);
  for (size_t i = 0; i < n; ++i) {
    const dvec3& normal = normals[i];
    dvec3 t = du[i] - normal * glm::dot(normal, du[i]);
    const double len = glm::length(t);
    if (!(len > 1e-12) || !std::isfinite(len)) {
      tangents[i] = vec4(any_perpendicular(vec3(normal)), 1.0f);
      continue;
    }
    t /= len;
    // glTF's v grows downward; the bitangent of an upward-v texture is -dP/dv.
    const double handedness = glm::dot(glm::cross(normal, t), -dv[i]) < 0.0 ? -1.0 : 1.0;
    tangents[i] = vec4(vec3(t), float(handedness));
  }
  return tangents;
}

}  // namespace kiln
