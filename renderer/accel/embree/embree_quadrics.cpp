#include "accel/embree/embree_quadrics.h"

#include <optional>

#include "core/float_bits.h"
#include "geometry/quadric.h"
#include "scene/shutter_motion.h"

namespace kiln {

namespace {

void quadric_bounds_callback(const RTCBoundsFunctionArguments* args) {
  const auto* p = static_cast<const prepared_quadric*>(args->geometryUserPtr);
  const bounds3 b = quadric_bounds(*p->shape);
  // Round outward to float so the box still contains the double-precision surface.
  args->bounds_o->lower_x = next_float_down(float(b.lower.x));
  args->bounds_o->lower_y = next_float_down(float(b.lower.y));
  args->bounds_o->lower_z = next_float_down(float(b.lower.z));
  args->bounds_o->upper_x = next_float_up(float(b.upper.x));
  args->bounds_o->upper_y = next_float_up(float(b.upper.y));
  args->bounds_o->upper_z = next_float_up(float(b.upper.z));
}

// The quadric hit of world ray `r` within [tnear, tfar] of the instance Embree is visiting: the
// closest, or with any_hit (occlusion) whichever is found first.
// A moving instance is taken back to object space by its transform at the ray's time.
std::optional<quadric_ray_hit> query(RTCIntersectContext* embree_context, const void* user, const ray& r,
                                     float tnear, float tfar, bool any_hit) {
  const auto* context = reinterpret_cast<const kiln_intersect_context*>(embree_context);
  const scene& world = *context->world;
  const uint32_t id = embree_context->instID[0];
  const dmat4 object_from_world = instance_moves(world, id) ? instance_at(world, id, r.time).object_from_world
                                                            : world.instances[id].object_from_world;
  const dvec3 o = transform_point(object_from_world, dvec3(r.origin));
  const dvec3 d = transform_vector(object_from_world, dvec3(r.direction));
  return intersect_quadric(*static_cast<const prepared_quadric*>(user), o, d, tnear, tfar, any_hit);
}

// Closest hits of N rays: one (rtcIntersect1) or a packet's lanes (a coherent stream's packets,
// handed to callbacks at the packet's own width), each lane its own world ray.
void quadric_intersect_callback(const RTCIntersectFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const kiln_intersect_context*>(args->context);
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    float& tfar = RTCRayN_tfar(rays, args->N, i);
    const ray& r = context->world_rays[RTCRayN_id(rays, args->N, i)];
    const std::optional<quadric_ray_hit> h =
        query(args->context, args->geometryUserPtr, r, RTCRayN_tnear(rays, args->N, i), tfar, false);
    if (!h) continue;
    tfar = float(h->t);
    // The accelerator rebuilds normal and UV from (t, part) in double: Ng, u, v are placeholders.
    RTCHitN_Ng_x(hits, args->N, i) = 0.0f;
    RTCHitN_Ng_y(hits, args->N, i) = 0.0f;
    RTCHitN_Ng_z(hits, args->N, i) = 1.0f;
    RTCHitN_u(hits, args->N, i) = 0.0f;
    RTCHitN_v(hits, args->N, i) = 0.0f;
    RTCHitN_primID(hits, args->N, i) = h->part;
    RTCHitN_geomID(hits, args->N, i) = args->geomID;
    RTCHitN_instID(hits, args->N, i, 0) = args->context->instID[0];
  }
}

// Occlusion of N rays: one (rtcOccluded1) or a packet's lanes (rtcOccluded4/8/16, which Embree 3
// hands to callbacks at the packet's own width and order), each lane its own world ray.
void quadric_occluded_callback(const RTCOccludedFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const kiln_intersect_context*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    float& tfar = RTCRayN_tfar(args->ray, args->N, i);
    const ray& r = context->world_rays[RTCRayN_id(args->ray, args->N, i)];
    // Any root in (tnear, tfar) blocks: no need to find the closest one.
    if (query(args->context, args->geometryUserPtr, r, RTCRayN_tnear(args->ray, args->N, i), tfar, true))
      tfar = -inf;
  }
}

}  // namespace

RTCScene build_quadric_scene(RTCDevice device, const prepared_quadric& q) {
  RTCScene quadric_scene = rtcNewScene(device);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, 1);
  rtcSetGeometryUserData(geometry, const_cast<prepared_quadric*>(&q));
  rtcSetGeometryBoundsFunction(geometry, &quadric_bounds_callback, nullptr);
  rtcSetGeometryIntersectFunction(geometry, &quadric_intersect_callback);
  rtcSetGeometryOccludedFunction(geometry, &quadric_occluded_callback);
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(quadric_scene, geometry, 0);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(quadric_scene);
  return quadric_scene;
}

}  // namespace kiln
