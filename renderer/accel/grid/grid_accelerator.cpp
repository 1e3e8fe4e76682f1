#include "accel/grid/grid_accelerator.h"

#include "accel/grid/grid_traversal.h"
#include "accel/grid/instance_shapes.h"
#include "geometry/triangle.h"

namespace kiln {

namespace {

// Closest hit over the scene, ties broken toward the lowest (instance, primitive).
struct closest_instance {
  float t;
  uint32_t instance = UINT32_MAX;
  shape_hit shape;
};

bool closer(float t, uint32_t inst, uint32_t prim, const closest_instance& best) {
  if (best.instance == UINT32_MAX) return true;
  if (t != best.t) return t < best.t;
  return inst != best.instance ? inst < best.instance : prim < best.shape.primitive;
}

}  // namespace

float_affine to_float_affine(const dmat4& m) {
  float_affine f;
  f.linear = mat3(dmat3(m));
  f.translation = vec3(dvec3(m[3]));
  return f;
}

void to_object_space(const float_affine& object_from_world, const ray& r, vec3& origin, vec3& direction) {
  origin = object_from_world.linear * r.origin + object_from_world.translation;
  direction = object_from_world.linear * r.direction;
}

grid_accelerator::grid_accelerator(const scene& s, const grid_options& options) : scene_(s) {
  // Unique meshes first, each built once, whatever the number of instances placing it.
  std::vector<bool> used(s.meshes.size(), false);
  for (const instance& inst : s.instances)
    if (inst.kind == shape_kind::mesh) used[inst.shape] = true;
  mesh_grids_.resize(s.meshes.size());
  for (size_t i = 0; i < s.meshes.size(); ++i)
    if (used[i]) mesh_grids_[i] = build_mesh_grid(s.meshes[i], options);

  object_from_world_.reserve(s.instances.size());
  for (const instance& inst : s.instances)
    object_from_world_.push_back(to_float_affine(inst.object_from_world));

  // The top level holds instance ids by world bounds; an instance is one opaque item there.
  auto bounds = [&s](uint32_t i) {
    const instance& inst = s.instances[i];
    return transform_bounds(inst.world_from_object, instance_object_bounds(s, inst));
  };
  auto overlaps = [&bounds](uint32_t i, const bounds3& box) {
    bounds3 b = bounds(i);
    return !(glm::any(glm::lessThan(b.upper, box.lower)) || glm::any(glm::greaterThan(b.lower, box.upper)));
  };
  top_ = build_grid(uint32_t(s.instances.size()), bounds, overlaps, options);
}

std::optional<hit> grid_accelerator::intersect(const ray& r) const {
  traversal_counters counters;
  return intersect(r, counters);
}

std::optional<hit> grid_accelerator::intersect(const ray& r, traversal_counters& counters) const {
  if (!is_valid(r) || top_.empty()) return std::nullopt;

  struct visitor {
    const grid_accelerator& self;
    const ray& world_ray;
    traversal_counters& counters;
    closest_instance best;
    mailbox tested;

    bool operator()(const grid_cell& cell, double t_exit) {
      for_each_untested(self.top_, cell, tested, [this](uint32_t id) {
        vec3 origin, direction;
        to_object_space(self.object_from_world_[id], world_ray, origin, direction);
        const float tmax = best.instance == UINT32_MAX ? world_ray.tmax : best.t;
        const mesh_grid* grid = self.mesh_grid_of(id);
        std::optional<shape_hit> h =
            intersect_instance_shape(self.scene_, id, world_ray, origin, direction, tmax, grid, counters);
        if (h && closer(h->t, id, h->primitive, best)) best = closest_instance{h->t, id, *h};
        return false;
      });
      return done_within(t_exit);
    }
    bool done_within(double t_exit) const { return best.instance != UINT32_MAX && double(best.t) <= t_exit; }
  };

  visitor visit{*this, r, counters, closest_instance{r.tmax, UINT32_MAX, {}}, {}};
  traverse_grid(top_, 0, dda_ray{dvec3(r.origin), dvec3(r.direction)}, r.tmin, r.tmax, visit, counters);
  if (visit.best.instance == UINT32_MAX) return std::nullopt;

  const closest_instance& best = visit.best;
  return finish_hit(scene_, r, best.t, best.instance, best.shape.primitive, best.shape.u, best.shape.v);
}

const mesh_grid* grid_accelerator::mesh_grid_of(uint32_t instance_id) const {
  const instance& inst = scene_.instances[instance_id];
  return inst.kind == shape_kind::mesh ? &mesh_grids_[inst.shape] : nullptr;
}

bool grid_accelerator::occluded(const ray& r) const {
  if (!is_valid(r) || top_.empty()) return false;
  traversal_counters counters;

  struct visitor {
    const grid_accelerator& self;
    const ray& world_ray;
    traversal_counters& counters;
    mailbox tested;

    bool operator()(const grid_cell& cell, double) {
      return for_each_untested(self.top_, cell, tested, [this](uint32_t id) {
        vec3 origin, direction;
        to_object_space(self.object_from_world_[id], world_ray, origin, direction);
        return occluded_instance_shape(self.scene_, id, world_ray, origin, direction, self.mesh_grid_of(id),
                                       counters);
      });
    }
    bool done_within(double) const { return false; }
  };

  visitor visit{*this, r, counters, {}};
  return traverse_grid(top_, 0, dda_ray{dvec3(r.origin), dvec3(r.direction)}, r.tmin, r.tmax, visit,
                       counters);
}

grid_statistics grid_accelerator::statistics() const {
  grid_statistics s;
  auto add = [&s](const grid& g) {
    s.nodes += g.nodes.size();
    s.cells += g.cells.size();
    s.item_references += g.items.size();
    s.memory_bytes += g.memory_bytes();
  };
  add(top_);
  for (const mesh_grid& m : mesh_grids_) add(m.cells);
  s.memory_bytes += object_from_world_.capacity() * sizeof(float_affine);
  return s;
}

}  // namespace kiln
