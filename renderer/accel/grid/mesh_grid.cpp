#include "accel/grid/mesh_grid.h"

#include "accel/grid/triangle_box.h"
#include "geometry/triangle.h"
#include "geometry/watertight_triangle.h"
#include "scene/alpha_coverage.h"

namespace kiln {

namespace {

// Closest hit: test the cell's triangles (each once per ray), keep the closest, and stop as soon
// as the closest hit lies inside the current cell: later cells hold only farther surfaces.
struct closest_visitor {
  const grid& g;
  const mesh& m;
  sheared_ray sheared;
  float tmin;
  float tmax;
  shape_hit& best;
  traversal_counters& counters;
  const alpha_filter& alpha;
  bool found = false;
  mailbox tested;

  bool operator()(const grid_cell& cell, double t_exit) {
    for_each_untested(g, cell, tested, [this](uint32_t primitive) {
      ++counters.items_tested;
      auto p = triangle_vertices(m, primitive);
      triangle_hit h;
      if (!intersect_watertight(sheared, p[0], p[1], p[2], tmin, found ? best.t : tmax, h)) return false;
      // A masked-out texel rejects the hit before it becomes `best`, as Embree's filter does.
      if (alpha.rejects(primitive, h.u, h.v)) return false;
      if (found && !(h.t < best.t || (h.t == best.t && primitive < best.primitive))) return false;
      best = shape_hit{h.t, primitive, h.u, h.v};
      found = true;
      return false;
    });
    return done_within(t_exit);
  }
  bool done_within(double t_exit) const { return found && double(best.t) <= t_exit; }
};

// Occlusion: the first hit anywhere on the segment answers the query.
struct any_visitor {
  const grid& g;
  const mesh& m;
  sheared_ray sheared;
  float tmin;
  float tmax;
  traversal_counters& counters;
  const alpha_filter& alpha;
  mailbox tested;

  bool operator()(const grid_cell& cell, double) {
    return for_each_untested(g, cell, tested, [this](uint32_t primitive) {
      ++counters.items_tested;
      auto p = triangle_vertices(m, primitive);
      triangle_hit h;
      return intersect_watertight(sheared, p[0], p[1], p[2], tmin, tmax, h) &&
             !alpha.rejects(primitive, h.u, h.v);
    });
  }
  bool done_within(double) const { return false; }
};

dda_ray to_dda(const vec3& origin, const vec3& direction) { return dda_ray{dvec3(origin), dvec3(direction)}; }

}  // namespace

bool alpha_filter::rejects(uint32_t primitive, float u, float v) const {
  return world != nullptr && alpha_masked_out(*world, instance, primitive, u, v);
}

alpha_filter alpha_filter_for(const scene& s, uint32_t instance_id) {
  const instance& inst = s.instances[instance_id];
  if (inst.kind != shape_kind::mesh || s.materials[inst.material].alpha != alpha_mode::mask) return {};
  return alpha_filter{&s, instance_id};
}

mesh_grid build_mesh_grid(const mesh& m, const grid_options& options) {
  auto bounds = [&m](uint32_t i) {
    bounds3 b;
    for (const vec3& p : triangle_vertices(m, i)) b.extend(dvec3(p));
    return b;
  };
  auto overlaps = [&m](uint32_t i, const bounds3& box) {
    auto p = triangle_vertices(m, i);
    return triangle_box_overlap(dvec3(p[0]), dvec3(p[1]), dvec3(p[2]), box);
  };
  return mesh_grid{build_grid(uint32_t(m.triangle_count()), bounds, overlaps, options)};
}

bool intersect_mesh_grid(const mesh_grid& g, const mesh& m, const vec3& origin, const vec3& direction,
                         float tmin, float tmax, shape_hit& best, traversal_counters& counters,
                         const alpha_filter& alpha) {
  if (g.cells.empty()) return false;
  closest_visitor visit{g.cells, m, shear_ray(origin, direction), tmin, tmax, best, counters, alpha,
                        false,   {}};
  traverse_grid(g.cells, 0, to_dda(origin, direction), tmin, tmax, visit, counters);
  return visit.found;
}

bool occluded_mesh_grid(const mesh_grid& g, const mesh& m, const vec3& origin, const vec3& direction,
                        float tmin, float tmax, traversal_counters& counters, const alpha_filter& alpha) {
  if (g.cells.empty()) return false;
  any_visitor visit{g.cells, m, shear_ray(origin, direction), tmin, tmax, counters, alpha, {}};
  return traverse_grid(g.cells, 0, to_dda(origin, direction), tmin, tmax, visit, counters);
}

}  // namespace kiln
