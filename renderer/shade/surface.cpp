#include "shade/surface.h"

#include "geometry/quadric.h"
#include "geometry/triangle.h"

namespace kiln {

namespace {

// A quadric hit: the point projected onto the exact surface with its error bound, the gradient
// normal (shading normal = geometric normal: the surface is exact) and the parametric UV.
surface_point make_quadric_surface_point(const scene& s, const instance& inst, const hit& h, const ray& r) {
  quadric_world_point w = quadric_world_hit(inst, s.quadrics[inst.shape], r, h.t, h.primitive_id);
  surface_point sp;
  sp.position = w.point;
  sp.position_error = w.error;
  sp.material = inst.material;
  sp.uv0 = w.uv;
  sp.uv1 = w.uv;  // a quadric has one parameterisation, used for every UV set
  // dp/du for normal mapping, with the glTF handedness of the part (docs/quadrics.md).
  sp.tangent = vec4(w.tangent, w.handedness);
  // Two-sided: the normal faces the incoming ray; front = arrived from outside (F > 0).
  sp.front_face = glm::dot(w.normal, r.direction) < 0.0f;
  sp.geometric_normal = sp.front_face ? w.normal : -w.normal;
  sp.shading_normal = sp.geometric_normal;
  return sp;
}

}  // namespace

surface_point make_surface_point(const scene& s, const hit& h, const ray& r) {
  const instance& inst = s.instances[h.instance_id];
  if (inst.kind == shape_kind::quadric) return make_quadric_surface_point(s, inst, h, r);
  const mesh& m = s.meshes[inst.shape];
  const uint32_t* idx = &m.indices[size_t(h.primitive_id) * 3];

  surface_point sp;
  surface_position pos = triangle_hit_position(inst, m, h.primitive_id, h.u, h.v);
  sp.position = pos.point;
  sp.position_error = pos.error;
  sp.material = inst.material;

  vec3 ng = h.geometric_normal;
  vec3 ns = ng;
  if (!m.normals.empty()) {
    vec3 n_object = interpolate(m.normals[idx[0]], m.normals[idx[1]], m.normals[idx[2]], h.u, h.v);
    dvec3 n_world = inst.world_from_object_normal * dvec3(n_object);
    double len = glm::length(n_world);
    if (len > 0.0 && std::isfinite(len)) ns = vec3(n_world / len);
  }
  if (!m.texcoords0.empty())
    sp.uv0 = interpolate(m.texcoords0[idx[0]], m.texcoords0[idx[1]], m.texcoords0[idx[2]], h.u, h.v);
  sp.uv1 = m.texcoords1.empty()
               ? sp.uv0
               : interpolate(m.texcoords1[idx[0]], m.texcoords1[idx[1]], m.texcoords1[idx[2]], h.u, h.v);
  if (!m.tangents.empty()) {
    const vec4 t = interpolate(m.tangents[idx[0]], m.tangents[idx[1]], m.tangents[idx[2]], h.u, h.v);
    // Tangents are directions on the surface: the linear part of world_from_object, not the
    // normal matrix. A mirroring transform flips cross(normal, tangent) against the transformed
    // bitangent, so it flips w as well.
    const dmat3 linear(inst.world_from_object);
    const bool mirrored = glm::determinant(linear) < 0.0;
    sp.tangent = vec4(vec3(linear * dvec3(vec3(t))), (t.w < 0.0f) != mirrored ? -1.0f : 1.0f);
  }
  if (!m.colors0.empty())
    sp.color0 = interpolate(m.colors0[idx[0]], m.colors0[idx[1]], m.colors0[idx[2]], h.u, h.v);

  // Two-sided shading: both normals face the incoming ray, and the shading normal never points
  // into the surface the geometric normal defines.
  sp.front_face = glm::dot(ng, r.direction) < 0.0f;
  if (!sp.front_face) {
    ng = -ng;
    ns = -ns;
  }
  if (glm::dot(ns, ng) < 0.0f) ns = glm::normalize(ns - 2.0f * glm::dot(ns, ng) * ng);
  sp.geometric_normal = ng;
  sp.shading_normal = ns;
  return sp;
}

}  // namespace kiln
