#include "accel/embree/embree_accelerator.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "accel/embree/embree_device.h"
#include "accel/embree/embree_quadrics.h"
#include "core/error.h"
#include "geometry/quadric.h"
#include "scene/alpha_coverage.h"
#include "scene/shutter_motion.h"

namespace kiln {

namespace {}  // namespace

// Embree reports errors through a C callback; the log records the first message and kiln throws
// after the Embree call has returned: after each build stage, and after rendering. The device is
// the process's (embree_device.h); this accelerator owns only its scenes.
struct embree_accelerator::state {
  RTCDevice device = nullptr;
  RTCScene top = nullptr;
  std::vector<RTCScene> mesh_scenes;
  std::vector<bool> refittable;  // per mesh: its BVH was built to be refitted (a moving mesh)
  std::vector<std::pair<size_t, size_t>> mesh_sizes;  // per refittable mesh: its vertex and index counts
  // Per instance, what it placed when built, and whether the top level holds it (its shape has a
  // scene: an empty mesh has none).
  std::vector<std::pair<shape_kind, uint32_t>> placed;
  std::vector<bool> attached;
  std::vector<RTCScene> quadric_scenes;         // one user-geometry scene per used quadric definition
  std::vector<prepared_quadric> quadric_forms;  // their callbacks' data; sized once, never moved
  embree_error_log errors;                      // this accelerator's build errors
  uint64_t unscoped_errors_before = 0;          // the process's traversal errors when it was built
  int64_t built_bytes = 0;                      // what its build added to Embree's memory
  int64_t peak_bytes = 0;                       // and the most the build held above its start
  bool has_quadrics = false;  // rtcIntersect1M cannot carry the world ray quadric callbacks read
  int packet_width = 1;       // occluded_batch's packets: the widest the CPU runs natively
  bool moving = false;        // built with motion blur: every frame is built anew

  void throw_if_failed(const std::string& during) const { errors.throw_if_any(during); }

  ~state() {
    if (top) rtcReleaseScene(top);
    for (RTCScene s : mesh_scenes)
      if (s) rtcReleaseScene(s);
    for (RTCScene s : quadric_scenes)
      if (s) rtcReleaseScene(s);
  }
};

namespace {

RTCBuildQuality embree_quality(bvh_quality q) {
  return q == bvh_quality::low    ? RTC_BUILD_QUALITY_LOW
         : q == bvh_quality::high ? RTC_BUILD_QUALITY_HIGH
                                  : RTC_BUILD_QUALITY_MEDIUM;
}

// The build settings every scene (each mesh's and the top level) gets.
void apply_build_options(RTCScene scene, const embree_options& o) {
  rtcSetSceneBuildQuality(scene, embree_quality(o.quality));
  rtcSetSceneFlags(scene, o.compact ? RTC_SCENE_FLAG_COMPACT : RTC_SCENE_FLAG_NONE);
}

// Intersection and occlusion filter for meshes placed with an alphaMode MASK material: a candidate
// hit where alpha < alphaCutoff is rejected, so the surface is neither seen nor casts a shadow.
// The mesh's geometry is shared by its instances, so the rule is looked up per hit through the
// instance id. Never throws (it runs inside Embree).
void alpha_mask_filter(const RTCFilterFunctionNArguments* args) {
  const auto& s = *static_cast<const scene*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned instance_id = RTCHitN_instID(args->hit, args->N, i, 0);
    const unsigned primitive_id = RTCHitN_primID(args->hit, args->N, i);
    if (instance_id >= s.instances.size()) continue;
    if (alpha_masked_out(s, instance_id, primitive_id, RTCHitN_u(args->hit, args->N, i),
                         RTCHitN_v(args->hit, args->N, i)))
      args->valid[i] = 0;
  }
}

// Builds the BVH of one mesh in its own object space. Positions are copied into an Embree-owned
// buffer because Embree reads vertices as 16-byte loads and needs padding past the last one.
// With alpha_filter the mask rule of the instances' materials is applied to every candidate hit.
// A moving mesh (refit) gets a scene that refits its BVH when its vertices change: Embree honours
// the geometry's RTC_BUILD_QUALITY_REFIT only in a scene of low build quality.
// With `steps` (motion blur) the mesh gets one vertex buffer per shutter step, which Embree
// interpolates linearly by the ray's time.
RTCScene build_mesh_scene(RTCDevice device, const mesh& m, const scene* alpha_filter,
                          const embree_options& options, bool refit = false,
                          const std::vector<std::vector<vec3>>* steps = nullptr) {
  RTCScene mesh_scene = rtcNewScene(device);
  apply_build_options(mesh_scene, options);
  if (refit) {
    rtcSetSceneBuildQuality(mesh_scene, RTC_BUILD_QUALITY_LOW);
    rtcSetSceneFlags(mesh_scene, RTC_SCENE_FLAG_DYNAMIC);
  }
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geometry, refit ? RTC_BUILD_QUALITY_REFIT : embree_quality(options.quality));
  const size_t step_count = steps ? steps->size() : 1;
  if (steps) rtcSetGeometryTimeStepCount(geometry, unsigned(step_count));
  for (size_t k = 0; k < step_count; ++k) {
    const std::vector<vec3>& positions = steps ? (*steps)[k] : m.positions;
    auto* vertices =
        static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, unsigned(k),
                                                    RTC_FORMAT_FLOAT3, sizeof(float) * 3, positions.size()));
    if (vertices) std::memcpy(vertices, positions.data(), positions.size() * sizeof(vec3));
  }
  auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(uint32_t) * 3, m.triangle_count()));
  if (indices) std::memcpy(indices, m.indices.data(), m.indices.size() * sizeof(uint32_t));
  if (alpha_filter) {
    rtcSetGeometryUserData(geometry, const_cast<scene*>(alpha_filter));
    rtcSetGeometryIntersectFilterFunction(geometry, &alpha_mask_filter);
    rtcSetGeometryOccludedFilterFunction(geometry, &alpha_mask_filter);
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(mesh_scene, geometry, 0);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(mesh_scene);
  return mesh_scene;
}

void set_instance_transform(RTCGeometry geometry, const dmat4& world_from_object, unsigned step = 0) {
  float columns[12];
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) columns[c * 3 + r] = float(world_from_object[c][r]);
  rtcSetGeometryTransform(geometry, step, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, columns);
}

// A moving instance's transform at every shutter step; Embree interpolates the matrices linearly
// by the ray's time (scene/shutter_motion.h does the same for shading).
void set_instance_motion(RTCGeometry geometry, const std::vector<dmat4>& steps) {
  rtcSetGeometryTimeStepCount(geometry, unsigned(steps.size()));
  for (size_t k = 0; k < steps.size(); ++k) set_instance_transform(geometry, steps[k], unsigned(k));
}

// Ray masks (scene.h's ray_may_hit): an instance the camera's own rays must pass by has the camera's
// bit cleared, and each instance has one of two bits for shadow rays: it stops light, or the shadow
// walk goes through it. Camera rays carry the camera's bit alone, a shadow ray that sees one kind
// of instance that kind's bit, every other ray all bits.
constexpr unsigned camera_ray_mask = 1u;
constexpr unsigned light_stopper_mask = 2u;
constexpr unsigned see_through_mask = 4u;
constexpr unsigned other_ray_mask = ~0u;
unsigned ray_mask(const ray& r) {
  if (r.kind == ray_kind::camera) return camera_ray_mask;
  if (r.sees == ray_sees::light_stoppers) return light_stopper_mask;
  if (r.sees == ray_sees::see_through_only) return see_through_mask;
  return other_ray_mask;
}

unsigned instance_mask(const scene& s, const instance& inst) {
  unsigned mask = ~(camera_ray_mask | light_stopper_mask | see_through_mask);
  if (camera_rays_hit(inst.holdout)) mask |= camera_ray_mask;
  mask |= shadow_walks_through(s, inst) ? see_through_mask : light_stopper_mask;
  return mask;
}

// Fills Embree's ray from r field by field, in place. Building a zero-initialised RTCRay and
// copying it into the query made GCC store 8 bytes and reload them as 16: a failed store-to-load
// forward that took half of intersect()'s own cycles.
void fill_embree_ray(const ray& r, RTCRay& out) {
  out.org_x = r.origin.x;
  out.org_y = r.origin.y;
  out.org_z = r.origin.z;
  out.tnear = r.tmin;
  out.dir_x = r.direction.x;
  out.dir_y = r.direction.y;
  out.dir_z = r.direction.z;
  out.time = r.time;
  out.tfar = r.tmax;
  out.mask = ray_mask(r);
  out.id = 0;
  out.flags = 0;
}

// The query of one ray, with no hit yet.
void fill_embree_query(const ray& r, RTCRayHit& query) {
  fill_embree_ray(r, query.ray);
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// Completes h, its query's fields already in it, on instance inst: the geometric normal in world
// space.
void finish_hit(const scene& world, const instance& inst, const RTCRayHit& query, const ray& r,
                bool quadric_normal, hit& h) {
  if (inst.kind == shape_kind::quadric) {
    // Quadric hits carry the part in primitive_id and (u, v) zero: shading finds the parametric UV
    // of the hits it shades (make_surface_point), and no other ray needs it (an atan2 and a
    // projection per reflection, refraction and culled hit saved).
    h.u = h.v = 0.0f;
    if (quadric_normal)
      h.geometric_normal = quadric_world_normal(inst, world.quadrics[inst.shape], r, h.t, h.primitive_id);
    return;
  }
  // Embree's Ng is the unnormalised cross(p1 - p0, p2 - p0) in the mesh's object space (instances
  // do not transform it): carried through the normal matrix it is the normal triangle_world_normal
  // computes, without fetching the three vertices again (camera rays 0.77x -> 0.84x the bare loop
  // on the demo). A reported hit has Ng·d != 0, so Ng is never zero.
  h.geometric_normal = vec3(
      glm::normalize(inst.world_from_object_normal * dvec3(query.hit.Ng_x, query.hit.Ng_y, query.hit.Ng_z)));
}

// finish_hit on a moving instance, where it is at the ray's time: its copy (some 400 bytes) is
// made only here, not zeroed on every hit of the still scenes that never need it.
[[gnu::noinline]] void moved_hit(const scene& world, const RTCRayHit& query, const ray& r,
                                 bool quadric_normal, hit& h) {
  finish_hit(world, instance_at(world, h.instance_id, r.time), query, r, quadric_normal, h);
}

// Writes into `out` kiln's hit record of an answered query of r (empty for a miss); without
// quadric_normal a quadric hit leaves its geometric normal zero (accelerator::intersect_for_shadow).
// Filled in place where the caller keeps it: a record built field by field and then copied whole
// stalls the copy's wide loads on store forwarding.
void kiln_hit(const scene& world, const RTCRayHit& query, const ray& r, bool quadric_normal,
              std::optional<hit>& out) {
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
    out.reset();
    return;
  }
  hit& h = out.emplace();
  h.t = query.ray.tfar;
  h.instance_id = query.hit.instID[0];
  h.primitive_id = query.hit.primID;
  h.u = query.hit.u;
  h.v = query.hit.v;
  // A moving instance's normal is the one of its transform at the ray's time.
  if (instance_moves(world, h.instance_id))
    moved_hit(world, query, r, quadric_normal, h);
  else
    finish_hit(world, world.instances[h.instance_id], query, r, quadric_normal, h);
}

// The widest ray packet this CPU traces natively (16 with AVX-512, 8 with AVX, 4 with SSE), or 1
// when Embree was built without packets. Wider packets emulated as narrower ones would only add
// the cost of the split.
int native_packet_width(RTCDevice device) {
  if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) return 16;
  if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) return 8;
  if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED)) return 4;
  return 1;
}

// Fills lane k of an SoA packet (RTCRay4/8/16) from r, in place; id is the lane's index into the
// rays the context's world_rays point at.
template <typename packet>
void fill_lane(const ray& r, unsigned id, packet& p, int k) {
  p.org_x[k] = r.origin.x;
  p.org_y[k] = r.origin.y;
  p.org_z[k] = r.origin.z;
  p.tnear[k] = r.tmin;
  p.dir_x[k] = r.direction.x;
  p.dir_y[k] = r.direction.y;
  p.dir_z[k] = r.direction.z;
  p.time[k] = r.time;
  p.tfar[k] = r.tmax;
  p.mask[k] = ray_mask(r);
  p.id[k] = id;
  p.flags[k] = 0;
}

// occluded() of each ray in packets of `width` lanes through trace (rtcOccluded4/8/16). An invalid
// ray, and the lanes past the end, are inactive: they hold a finite empty ray, since Embree loads
// every lane, and answer not blocked as occluded() does.
template <int width, typename packet>
void occlude_packets(RTCScene top, const scene& world, const ray* rays, size_t count, uint8_t* blocked,
                     void (*trace)(const int*, RTCScene, RTCIntersectContext*, packet*)) {
  static const ray empty_lane{vec3(0.0f), vec3(0.0f, 0.0f, 1.0f), 0.0f, 0.0f};
  kiln_intersect_context context;
  context.world = &world;
  for (size_t begin = 0; begin < count; begin += width) {
    const size_t n = std::min(size_t(width), count - begin);
    packet p;  // aligned to its width by its declaration, as rtcOccludedN requires
    alignas(64) int valid[width];
    bool any = false;
    for (int k = 0; k < width; ++k) {
      const bool active = size_t(k) < n && is_valid(rays[begin + k]);
      valid[k] = active ? -1 : 0;
      any |= active;
      fill_lane(active ? rays[begin + k] : empty_lane, unsigned(k), p, k);
    }
    if (any) {
      // A fresh context per packet, as per ray in trace_bare: an occlusion query that stops inside
      // an instance leaves the context's instance stack behind.
      rtcInitIntersectContext(&context.embree);
      context.world_rays = rays + begin;
      trace(valid, top, &context.embree, &p);
    }
    // Embree marks an occluded lane by setting its tfar to -infinity.
    for (size_t k = 0; k < n; ++k) blocked[begin + k] = valid[k] != 0 && p.tfar[k] < 0.0f;
  }
}

}  // namespace

embree_accelerator::embree_accelerator(const scene& s, const embree_options& options)
    : state_(std::make_unique<state>()), scene_(s), options_(options) {
  state_->device = process_embree_device();
  state_->packet_width = native_packet_width(state_->device);
  embree_error_scope scope(state_->errors);
  state_->unscoped_errors_before = unscoped_embree_errors();
  const int64_t bytes_before = embree_bytes_now();
  reset_embree_peak();

  // Unique meshes first, built once, however many instances place them.
  state_->mesh_scenes.assign(s.meshes.size(), nullptr);
  state_->refittable.assign(s.meshes.size(), false);
  state_->mesh_sizes.assign(s.meshes.size(), {0, 0});
  std::vector<bool> used(s.meshes.size(), false);
  std::vector<bool> used_quadric(s.quadrics.size(), false);
  for (const instance& inst : s.instances)
    (inst.kind == shape_kind::quadric ? used_quadric : used)[inst.shape] = true;
  const std::vector<bool> masked = meshes_needing_alpha_filter(s);
  state_->moving = s.shutter.any();
  for (uint32_t i = 0; i < s.meshes.size(); ++i)
    if (used[i] && s.meshes[i].triangle_count() > 0)
      state_->mesh_scenes[i] =
          build_mesh_scene(state_->device, s.meshes[i], masked[i] ? &s : nullptr, options_, false,
                           mesh_deforms(s, i) ? &s.shutter.mesh_positions[i] : nullptr);
  state_->throw_if_failed("building mesh BVHs");
  // Each quadric definition is one user-geometry scene, however many nodes place it.
  state_->quadric_scenes.assign(s.quadrics.size(), nullptr);
  state_->quadric_forms.resize(s.quadrics.size());
  for (size_t i = 0; i < s.quadrics.size(); ++i)
    if (used_quadric[i]) {
      state_->quadric_forms[i] = prepare_quadric(s.quadrics[i]);
      state_->quadric_scenes[i] = build_quadric_scene(state_->device, state_->quadric_forms[i]);
      state_->has_quadrics = true;
    }
  state_->throw_if_failed("building quadric geometry");

  state_->top = rtcNewScene(state_->device);
  apply_build_options(state_->top, options_);
  state_->placed.reserve(s.instances.size());
  for (size_t i = 0; i < s.instances.size(); ++i) {
    const instance& inst = s.instances[i];
    state_->placed.emplace_back(inst.kind, inst.shape);
    state_->attached.push_back(false);
    RTCScene shape = inst.kind == shape_kind::quadric ? state_->quadric_scenes[inst.shape]
                                                      : state_->mesh_scenes[inst.shape];
    if (!shape) continue;
    RTCGeometry geometry = rtcNewGeometry(state_->device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geometry, shape);
    rtcSetGeometryMask(geometry, instance_mask(s, inst));
    if (instance_moves(s, uint32_t(i)))
      set_instance_motion(geometry, s.shutter.instance_steps[i]);
    else
      set_instance_transform(geometry, inst.world_from_object);
    rtcCommitGeometry(geometry);
    // The geometry id is the instance index, so a hit names its instance directly.
    rtcAttachGeometryByID(state_->top, geometry, unsigned(i));
    state_->attached.back() = true;
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(state_->top);
  state_->throw_if_failed("building the instance BVH");
  state_->built_bytes = embree_bytes_now() - bytes_before;
  state_->peak_bytes = embree_peak_bytes_since_reset() - bytes_before;
}

embree_accelerator::~embree_accelerator() = default;

bool embree_accelerator::update(const std::vector<uint32_t>& changed_meshes) {
  const scene& s = scene_;
  state& st = *state_;
  // Motion blur's time steps are built in, not refitted: a moving scene is built anew each frame.
  if (st.moving || s.shutter.any()) return false;
  if (s.meshes.size() != st.mesh_scenes.size() || s.instances.size() != st.placed.size()) return false;
  for (size_t i = 0; i < s.instances.size(); ++i)
    if (st.placed[i] != std::make_pair(s.instances[i].kind, s.instances[i].shape)) return false;
  if (s.quadrics.size() != st.quadric_forms.size()) return false;
  // A frame's scene holds its own copy of the (never animated) quadric definitions: the callbacks'
  // forms must point at this frame's, not the last frame's, which are gone.
  for (size_t i = 0; i < s.quadrics.size(); ++i) st.quadric_forms[i].shape = &s.quadrics[i];
  embree_error_scope scope(st.errors);
  const std::vector<bool> masked = meshes_needing_alpha_filter(s);
  std::vector<bool> rebuilt(s.meshes.size(), false);
  for (uint32_t m : changed_meshes) {
    if (m >= s.meshes.size() || st.mesh_scenes[m] == nullptr) continue;  // placed by no instance
    const mesh& src = s.meshes[m];
    if (st.refittable[m] && st.mesh_sizes[m] == std::make_pair(src.positions.size(), src.indices.size()) &&
        std::memcmp(rtcGetGeometryBufferData(rtcGetGeometry(st.mesh_scenes[m], 0), RTC_BUFFER_TYPE_INDEX, 0),
                    src.indices.data(), src.indices.size() * sizeof(uint32_t)) == 0) {
      RTCGeometry geometry = rtcGetGeometry(st.mesh_scenes[m], 0);
      std::memcpy(rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_VERTEX, 0), src.positions.data(),
                  src.positions.size() * sizeof(vec3));
      rtcUpdateGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0);
      rtcCommitGeometry(geometry);
      rtcCommitScene(st.mesh_scenes[m]);
      continue;
    }
    rtcReleaseScene(st.mesh_scenes[m]);
    st.mesh_scenes[m] = build_mesh_scene(st.device, src, masked[m] ? &s : nullptr, options_, true);
    st.mesh_sizes[m] = {src.positions.size(), src.indices.size()};
    st.refittable[m] = true;
    rebuilt[m] = true;
  }
  st.throw_if_failed("refitting the moving meshes' BVHs");
  for (size_t i = 0; i < s.instances.size(); ++i) {
    const instance& inst = s.instances[i];
    if (!st.attached[i]) continue;  // its shape has no triangles
    RTCGeometry geometry = rtcGetGeometry(st.top, unsigned(i));
    if (inst.kind == shape_kind::mesh && rebuilt[inst.shape])
      rtcSetGeometryInstancedScene(geometry, st.mesh_scenes[inst.shape]);
    rtcSetGeometryMask(geometry, instance_mask(s, inst));  // this frame's materials and holdouts
    set_instance_transform(geometry, inst.world_from_object);
    rtcCommitGeometry(geometry);
  }
  rtcCommitScene(st.top);
  st.throw_if_failed("moving the instances");
  return true;
}

void embree_accelerator::throw_if_failed() const {
  state_->throw_if_failed("tracing rays");
  if (unscoped_embree_errors() != state_->unscoped_errors_before)
    unscoped_embree_error_log().throw_if_any("tracing rays");
}

std::optional<hit> embree_accelerator::intersect(const ray& r) const {
  std::optional<hit> out;
  closest_hit(r, true, out);
  return out;
}

std::optional<hit> embree_accelerator::intersect_for_shadow(const ray& r) const {
  std::optional<hit> out;
  closest_hit(r, false, out);
  return out;
}

void embree_accelerator::closest_hit(const ray& r, bool quadric_normal, std::optional<hit>& out) const {
  if (!is_valid(r)) {
    out.reset();
    return;
  }
  kiln_intersect_context context;
  rtcInitIntersectContext(&context.embree);
  context.world = &scene_;
  context.world_rays = &r;
  RTCRayHit query;
  fill_embree_query(r, query);
  rtcIntersect1(state_->top, &context.embree, &query);
  kiln_hit(scene_, query, r, quadric_normal, out);
}

void embree_accelerator::intersect_coherent(const ray* rays, size_t count, std::optional<hit>* out) const {
  // Invalid rays never reach Embree; the stream holds the others in order, each with its index in
  // rays as its id (quadric callbacks read the double-precision world ray by it).
  thread_local std::vector<RTCRayHit> queries;
  thread_local std::vector<uint32_t> index;
  queries.clear();
  index.clear();
  for (size_t i = 0; i < count; ++i) {
    out[i].reset();
    if (!is_valid(rays[i])) continue;
    RTCRayHit& query = queries.emplace_back();
    fill_embree_query(rays[i], query);
    query.ray.id = unsigned(i);
    index.push_back(uint32_t(i));
  }
  if (queries.empty()) return;
  kiln_intersect_context context;
  rtcInitIntersectContext(&context.embree);
  context.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  context.world = &scene_;
  context.world_rays = rays;
  rtcIntersect1M(state_->top, &context.embree, queries.data(), unsigned(queries.size()), sizeof(RTCRayHit));
  for (size_t k = 0; k < queries.size(); ++k)
    kiln_hit(scene_, queries[k], rays[index[k]], true, out[index[k]]);
}

size_t embree_accelerator::embree_bytes() const { return size_t(std::max<int64_t>(0, state_->built_bytes)); }
size_t embree_accelerator::embree_peak_bytes() const {
  return size_t(std::max<int64_t>(0, state_->peak_bytes));
}

bool embree_accelerator::occluded(const ray& r) const {
  if (!is_valid(r)) return false;
  kiln_intersect_context context;
  rtcInitIntersectContext(&context.embree);
  context.world = &scene_;
  context.world_rays = &r;
  RTCRay query;
  fill_embree_ray(r, query);
  rtcOccluded1(state_->top, &context.embree, &query);
  // Embree marks an occluded ray by setting tfar to -infinity.
  return query.tfar < 0.0f;
}

void embree_accelerator::occluded_batch(const ray* rays, size_t count, uint8_t* blocked) const {
  switch (state_->packet_width) {
    case 16:
      occlude_packets<16>(state_->top, scene_, rays, count, blocked, &rtcOccluded16);
      return;
    case 8:
      occlude_packets<8>(state_->top, scene_, rays, count, blocked, &rtcOccluded8);
      return;
    case 4:
      occlude_packets<4>(state_->top, scene_, rays, count, blocked, &rtcOccluded4);
      return;
    default:
      for (size_t i = 0; i < count; ++i) blocked[i] = occluded(rays[i]);
  }
}

}  // namespace kiln

namespace kiln {

std::string embree_version() { return RTC_VERSION_STRING; }

size_t embree_accelerator::trace_bare(const ray* rays, size_t count, bool occlusion) const {
  kiln_intersect_context context;
  context.world = &scene_;
  size_t hits = 0;
  for (size_t i = 0; i < count; ++i) {
    // A fresh context per ray, as Embree requires: an occlusion query that stops inside an instance
    // leaves the context's instance stack behind.
    rtcInitIntersectContext(&context.embree);
    context.world_rays = &rays[i];  // quadric user geometry reads the double-precision world ray
    if (occlusion) {
      RTCRay query;
      fill_embree_ray(rays[i], query);
      rtcOccluded1(state_->top, &context.embree, &query);
      hits += query.tfar < 0.0f;
    } else {
      RTCRayHit query;
      fill_embree_query(rays[i], query);
      rtcIntersect1(state_->top, &context.embree, &query);
      hits += query.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
  }
  return hits;
}

size_t embree_accelerator::trace_bare_stream(const ray* rays, size_t count) const {
  thread_local std::vector<RTCRayHit> queries;
  queries.resize(count);
  for (size_t i = 0; i < count; ++i) fill_embree_query(rays[i], queries[i]);
  kiln_intersect_context context;
  rtcInitIntersectContext(&context.embree);
  context.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  context.world = &scene_;
  rtcIntersect1M(state_->top, &context.embree, queries.data(), unsigned(count), sizeof(RTCRayHit));
  size_t hits = 0;
  for (const RTCRayHit& q : queries) hits += q.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  return hits;
}

bool embree_accelerator::streams_supported() const { return !state_->has_quadrics; }

}  // namespace kiln
