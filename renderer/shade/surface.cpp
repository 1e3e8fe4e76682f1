#include "shade/surface.h"

#include <algorithm>
#include <cmath>

#include "geometry/quadric.h"
#include "geometry/triangle.h"
#include "scene/shutter_motion.h"

namespace kiln {

namespace {

// The footprint in UV space of a cone of width `cone_width` arriving along unit `direction` at a
// surface with unit normal n, whose UV-to-world Jacobian has columns dp_du, dp_dv: the circular cross
// section stretches by 1/|cos θ| along the projected ray direction (the ellipse's major axis) and
// keeps its width across it. Axes that dp_du, dp_dv cannot express are dropped (degenerate UVs).
// Inlined into the shading points below: called, its result came back in two registers that GCC
// stored to the stack as overlapping 16- and 8-byte halves and read back whole, a store-forwarding
// stall on every textured hit.
[[gnu::always_inline]] inline uv_footprint footprint_from_jacobian(const vec3& dp_du, const vec3& dp_dv,
                                                                   const vec3& n, const vec3& direction,
                                                                   float cone_width) {
  uv_footprint fp;
  if (!(cone_width > 0.0f)) return fp;
  // The ellipse's axes on the tangent plane: along the projected ray direction (stretched by
  // 1/|cos θ|, clamped so that grazing rays stay finite) and across it.
  const float cos_theta = std::max(std::abs(glm::dot(direction, n)), 1e-4f);
  vec3 along = direction - glm::dot(direction, n) * n;
  float along_length = glm::length(along);
  if (!(along_length > 1e-6f)) {
    along = dp_du - glm::dot(dp_du, n) * n;  // normal incidence: the circle, any axis will do
    along_length = glm::length(along);
    if (!(along_length > 0.0f)) return fp;
  }
  along /= along_length;
  const vec3 across = glm::cross(n, along);
  const vec3 axis_x = along * (cone_width / cos_theta);
  const vec3 axis_y = across * cone_width;
  // Express each axis in the basis (dp_du, dp_dv): a = α·dp_du + β·dp_dv solved through the Gram
  // matrix (a least-squares fit for axes slightly off the plane); (α, β) is then the UV change.
  const double g11 = glm::dot(dp_du, dp_du), g12 = glm::dot(dp_du, dp_dv), g22 = glm::dot(dp_dv, dp_dv);
  const double det = g11 * g22 - g12 * g12;
  if (!(det > 1e-12 * g11 * g22) || !std::isfinite(det)) return fp;
  auto to_uv = [&](const vec3& a) {
    const double r1 = glm::dot(a, dp_du), r2 = glm::dot(a, dp_dv);
    return vec2(float((g22 * r1 - g12 * r2) / det), float((g11 * r2 - g12 * r1) / det));
  };
  fp.dx = to_uv(axis_x);
  fp.dy = to_uv(axis_y);
  return fp;
}

// dP/du and dP/dv of a triangle (world space) for one UV set, from its edges: [e1 e2] = J·[Δuv1 Δuv2].
// Degenerate UVs (zero area in UV space) give zero vectors, so the footprint stays empty.
void triangle_uv_jacobian(const vec3 p[3], const vec2 uv[3], vec3& dp_du, vec3& dp_dv) {
  const vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
  const vec2 d1 = uv[1] - uv[0], d2 = uv[2] - uv[0];
  const float det = d1.x * d2.y - d1.y * d2.x;
  if (!(std::abs(det) > 0.0f) || !std::isfinite(det)) {
    dp_du = dp_dv = vec3(0.0f);
    return;
  }
  dp_du = (e1 * d2.y - e2 * d1.y) / det;
  dp_dv = (e2 * d1.x - e1 * d2.x) / det;
}

// Whether a hit on material m needs a curvature estimate: its roughness may be below
// curvature_roughness_limit (a texture can lower any factor).
bool may_be_smooth(const material& m) {
  return m.roughness_factor < curvature_roughness_limit || m.metallic_roughness_texture.present();
}

// A quadric hit: the point projected onto the exact surface with its error bound, the gradient
// normal (shading normal = geometric normal: the surface is exact) and the parametric UV.
surface_point make_quadric_surface_point(const scene& s, const instance& inst, const hit& h, const ray& r,
                                         float cone_width) {
  const quadric& q = s.quadrics[inst.shape];
  // One projection onto the surface serves the point, the UV footprint and the curvature.
  const quadric_surface object = quadric_surface_of_hit(inst, q, r, h.t, h.primitive_id);
  quadric_world_point w = quadric_world_point_of(inst, object);
  surface_point sp;
  sp.instance = h.instance_id;
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
  sp.smooth_normal = sp.geometric_normal;
  sp.smooth_position = sp.position;
  if (!(cone_width > 0.0f)) return sp;
  const material& m = s.materials[inst.material];
  // The UV footprint only feeds texture lookups: an untextured material skips its four extra
  // projections and UV evaluations (the image cannot change; the footprint stays empty).
  vec3 dp_du, dp_dv;
  if (samples_textures(m)) {
    if (!quadric_world_uv_jacobian(inst, q, h.primitive_id, object, dp_du, dp_dv)) return sp;
    sp.footprint0 =
        footprint_from_jacobian(dp_du, dp_dv, sp.geometric_normal, glm::normalize(r.direction), cone_width);
    sp.footprint1 = sp.footprint0;
  }
  if (may_be_smooth(m)) {
    // The quadric's two principal turns: a cylinder's highlight widens around it, not along it.
    const quadric_normal_turns t = quadric_world_normal_turns(inst, q, h.primitive_id, object);
    if (t.valid)
      sp.curvature = curvature_from_differentials(t.normal, t.step[0], t.step[1], t.turn[0], t.turn[1]);
  }
  return sp;
}

// The triangle's curvature as its vertex normals describe them (the normal interpolated across
// it), in object space (glTF normals are unit), carried to world units by the instance's mean scale
// (the cube root of its determinant; exact for uniform scales).
surface_curvature triangle_curvature(const instance& inst, const mesh& m, const uint32_t* idx,
                                     const dvec3 unit_normal[3]) {
  const dvec3 p0(m.positions[idx[0]]);
  const dvec3 mean = unit_normal[0] + unit_normal[1] + unit_normal[2];
  const double mean_length = glm::length(mean);
  if (!(mean_length > 0.0)) return {};
  surface_curvature c = curvature_from_differentials(
      mean / mean_length, dvec3(m.positions[idx[1]]) - p0, dvec3(m.positions[idx[2]]) - p0,
      unit_normal[1] - unit_normal[0], unit_normal[2] - unit_normal[0]);
  const double scale = inst.mean_scale;
  if (!(scale > 0.0)) return {};
  c.major = float(c.major / scale);
  c.minor = float(c.minor / scale);
  if (c.axis != vec3(0.0f)) {
    const dvec3 world_axis = transform_vector(inst.world_from_object, dvec3(c.axis));
    const double length = glm::length(world_axis);
    c.axis = length > 0.0 ? vec3(world_axis / length) : vec3(0.0f);
  }
  if (!std::isfinite(c.major) || !std::isfinite(c.minor)) return {};
  return c;
}

// The constants of triangle idx of mesh m placed by inst (see triangle_constants), the footprint's
// part only when `footprint`.
void fill_triangle_constants(const scene& s, const instance& inst, const mesh& m, const uint32_t* idx,
                             bool footprint, triangle_constants& c) {
  c.inst = &inst;
  c.idx = idx;
  c.footprint = footprint;
  if (!m.normals.empty())
    for (int k = 0; k < 3; ++k) c.unit_normal[k] = glm::normalize(dvec3(m.normals[idx[k]]));
  if (!footprint) return;
  const material& mat = s.materials[inst.material];
  c.curvature = !m.normals.empty() && may_be_smooth(mat) ? triangle_curvature(inst, m, idx, c.unit_normal)
                                                         : surface_curvature{};
  // As for quadrics: the UV footprints only feed texture lookups, so an untextured material
  // (ToyCar's glass, say) skips them.
  if (!samples_textures(mat)) return;
  vec3 p[3];
  for (int k = 0; k < 3; ++k)
    p[k] = vec3(transform_point(inst.world_from_object, dvec3(m.positions[idx[k]])));
  const std::vector<vec2>* sets[2] = {&m.texcoords0, &m.texcoords1};
  for (int set = 0; set < 2; ++set) {
    if (sets[set]->empty()) continue;
    const std::vector<vec2>& uv = *sets[set];
    const vec2 corners[3] = {uv[idx[0]], uv[idx[1]], uv[idx[2]]};
    triangle_uv_jacobian(p, corners, c.dp_du[set], c.dp_dv[set]);
  }
}

// The constants of the hit triangle: from memo when it holds them, else computed (and kept there).
const triangle_constants& constants_of(const scene& s, const instance& inst, const mesh& m,
                                       const uint32_t* idx, bool footprint, triangle_memo* memo,
                                       triangle_constants& scratch) {
  if (!memo) {
    fill_triangle_constants(s, inst, m, idx, footprint, scratch);
    return scratch;
  }
  for (triangle_constants& c : memo->entries)
    if (c.idx == idx && c.inst == &inst) {
      if (footprint && !c.footprint) fill_triangle_constants(s, inst, m, idx, true, c);
      return c;
    }
  triangle_constants& c = memo->entries[memo->next];
  memo->next = (memo->next + 1) % triangle_memo::size;
  fill_triangle_constants(s, inst, m, idx, footprint, c);
  return c;
}

// Hanika's shadow-terminator offset in object space: from the hit to the blend, by barycentrics,
// of its projections onto the vertices' tangent planes, each taken only where that plane lies
// above the hit (outward: concave parts keep the flat point). unit_normal: the vertex normals;
// front: as stored (true) or flipped toward a back-face ray.
dvec3 smooth_surface_lift(const mesh& m, const uint32_t* idx, const dvec3 unit_normal[3], float u, float v,
                          bool front) {
  const double w[3] = {1.0 - double(u) - double(v), double(u), double(v)};
  dvec3 p(0.0);
  for (int k = 0; k < 3; ++k) p += w[k] * dvec3(m.positions[idx[k]]);
  dvec3 lift(0.0);
  for (int k = 0; k < 3; ++k) {
    const dvec3 n = front ? unit_normal[k] : -unit_normal[k];
    const double height = glm::dot(p - dvec3(m.positions[idx[k]]), n);
    if (height < 0.0 && std::isfinite(height)) lift -= w[k] * height * n;
  }
  return lift;
}

// The shading point of hit h on triangle `primitive` (corners idx) of mesh m placed by inst.
surface_point make_triangle_surface_point(const scene& s, const instance& inst, const mesh& m,
                                          uint32_t primitive, const hit& h, const ray& r, float cone_width,
                                          triangle_memo* memo) {
  const uint32_t* idx = &m.indices[size_t(primitive) * 3];
  triangle_constants scratch;
  const triangle_constants& c = constants_of(s, inst, m, idx, cone_width > 0.0f, memo, scratch);
  surface_point sp;
  sp.instance = h.instance_id;
  surface_position pos = triangle_hit_position(inst, m, primitive, h.u, h.v);
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
    sp.tangent = vec4(vec3(linear * dvec3(vec3(t))), (t.w < 0.0f) != inst.mirrored ? -1.0f : 1.0f);
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
  sp.smooth_normal = ns;
  sp.smooth_position = sp.position;
  if (!m.normals.empty()) {
    const dvec3 lift = smooth_surface_lift(m, idx, c.unit_normal, h.u, h.v, sp.front_face);
    if (lift != dvec3(0.0)) {
      const dvec3 world_lift = transform_vector(inst.world_from_object, lift);
      if (is_finite(world_lift)) sp.smooth_position = vec3(dvec3(sp.position) + world_lift);
    }
  }
  if (cone_width > 0.0f) {
    sp.curvature = c.curvature;
    if (samples_textures(s.materials[inst.material])) {
      const vec3 direction = glm::normalize(r.direction);
      if (!m.texcoords0.empty())
        sp.footprint0 = footprint_from_jacobian(c.dp_du[0], c.dp_dv[0], ng, direction, cone_width);
      sp.footprint1 = m.texcoords1.empty()
                          ? sp.footprint0
                          : footprint_from_jacobian(c.dp_du[1], c.dp_dv[1], ng, direction, cone_width);
    }
  }
  return sp;
}

// Triangle `primitive` of a deforming mesh at `time`, as a mesh of its own three corners (held per
// thread, valid until the next call), so that the code for still meshes shades it unchanged.
// Tangents keep the frame's own: the shutter steps do not carry them.
const mesh& triangle_at_time(const scene& s, uint32_t mesh_index, uint32_t primitive, float time) {
  thread_local mesh corners;
  const mesh& m = s.meshes[mesh_index];
  const uint32_t* idx = &m.indices[size_t(primitive) * 3];
  const std::array<vec3, 3> p = triangle_positions_at(s, mesh_index, idx, time);
  corners.positions.assign(p.begin(), p.end());
  corners.indices = {0, 1, 2};
  auto pick = [idx](const auto& from, auto& to) {
    to.clear();
    if (!from.empty()) to = {from[idx[0]], from[idx[1]], from[idx[2]]};
  };
  corners.normals.clear();
  if (!m.normals.empty()) {
    const std::array<vec3, 3> n = triangle_normals_at(s, mesh_index, idx, time);
    corners.normals.assign(n.begin(), n.end());
  }
  pick(m.texcoords0, corners.texcoords0);
  pick(m.texcoords1, corners.texcoords1);
  pick(m.colors0, corners.colors0);
  pick(m.tangents, corners.tangents);
  return corners;
}

// Embree interpolates a moving surface in float; the point rebuilt here may differ from the one
// it intersected by a few ulps of the coordinates that went into it.
vec3 interpolation_error(const surface_point& sp, const instance& inst) {
  const vec3 t = glm::abs(vec3(dvec3(inst.world_from_object[3])));
  const vec3 reach = glm::abs(sp.position) + vec3(std::max({t.x, t.y, t.z}));
  return 8.0f * machine_epsilon * reach;
}

// The shading point of h on inst's shape (inst where it is at the ray's time, moved when it moves);
// memo only for a still instance, whose address is a key.
surface_point shape_surface_point(const scene& s, const instance& inst, bool moved, bool deforms,
                                  const hit& h, const ray& r, float cone_width, triangle_memo* memo) {
  if (inst.kind == shape_kind::quadric) return make_quadric_surface_point(s, inst, h, r, cone_width);
  if (deforms)
    return make_triangle_surface_point(s, inst, triangle_at_time(s, inst.shape, h.primitive_id, r.time), 0, h,
                                       r, cone_width, nullptr);
  return make_triangle_surface_point(s, inst, s.meshes[inst.shape], h.primitive_id, h, r, cone_width,
                                     moved ? nullptr : memo);
}

// make_surface_point on instance inst (s.instances[h.instance_id], or a moving one where it is at
// the ray's time, moved).
surface_point surface_point_on(const scene& s, const instance& inst, bool moved, const hit& h, const ray& r,
                               float cone_width, triangle_memo* memo) {
  const bool deforms = inst.kind == shape_kind::mesh && mesh_deforms(s, inst.shape);
  // Built in place by the return above, rather than zeroed here and then assigned.
  surface_point sp = shape_surface_point(s, inst, moved, deforms, h, r, cone_width, memo);
  if (moved || deforms) sp.position_error += interpolation_error(sp, inst);
  sp.time = r.time;
  return sp;
}

// The moving case apart: the instance's copy at the ray's time (some 400 bytes) is made only here,
// not zeroed on every call for the still scenes that never need it.
[[gnu::noinline]] surface_point moved_surface_point(const scene& s, const hit& h, const ray& r,
                                                    float cone_width) {
  const instance moved = instance_at(s, h.instance_id, r.time);
  return surface_point_on(s, moved, true, h, r, cone_width, nullptr);
}

}  // namespace

surface_curvature curvature_from_differentials(const dvec3& n, const dvec3& dp1, const dvec3& dp2,
                                               const dvec3& dn1, const dvec3& dn2) {
  // An orthonormal basis (t, b) across n; the steps and normal changes in it.
  dvec3 t = dp1 - n * glm::dot(n, dp1);
  const double t_length = glm::length(t);
  if (!(t_length > 0.0)) return {};
  t /= t_length;
  const dvec3 b = glm::cross(n, t);
  const glm::dmat2 steps(glm::dot(dp1, t), glm::dot(dp1, b), glm::dot(dp2, t), glm::dot(dp2, b));
  const glm::dmat2 turns(glm::dot(dn1, t), glm::dot(dn1, b), glm::dot(dn2, t), glm::dot(dn2, b));
  const double det = glm::determinant(steps);
  const double size = glm::length(dp1) * glm::length(dp2);
  if (!(std::abs(det) > 1e-9 * size) || !std::isfinite(det)) return {};
  // turn_per_length maps a step (in t, b) to the normal's change; its singular values are the
  // square roots of the eigenvalues of the symmetric turn · turnᵀ, whose eigenvectors are the
  // directions the normal tilts in.
  const glm::dmat2 turn_per_length = turns * glm::inverse(steps);
  const glm::dmat2 spread = turn_per_length * glm::transpose(turn_per_length);
  const double a = spread[0][0], d = spread[1][1], off = spread[1][0];
  const double half_trace = 0.5 * (a + d);
  const double gap = std::sqrt(std::max(0.25 * (a - d) * (a - d) + off * off, 0.0));
  const double largest = half_trace + gap, smallest = std::max(half_trace - gap, 0.0);
  surface_curvature c;
  c.major = float(std::sqrt(largest));
  c.minor = float(std::sqrt(smallest));
  // The eigenvector of the largest eigenvalue: (off, largest - a) or (largest - d, off), whichever
  // is longer (both vanish when the turn is the same every way: no axis then).
  glm::dvec2 e1(off, largest - a), e2(largest - d, off);
  const glm::dvec2 e = glm::dot(e1, e1) > glm::dot(e2, e2) ? e1 : e2;
  const double e_length = glm::length(e);
  if (gap > 1e-6 * half_trace && e_length > 0.0) c.axis = vec3((t * e.x + b * e.y) / e_length);
  return c;
}

surface_point make_surface_point(const scene& s, const hit& h, const ray& r, float cone_width,
                                 triangle_memo* memo) {
  // A moving instance or deforming mesh is shaded where it is at the ray's time.
  if (instance_moves(s, h.instance_id)) return moved_surface_point(s, h, r, cone_width);
  return surface_point_on(s, s.instances[h.instance_id], false, h, r, cone_width, memo);
}

}  // namespace kiln
