// Quadrics as Embree user geometry (RTC_GEOMETRY_TYPE_USER): one scene per distinct KILN_quadric
// definition, placed by instances exactly like meshes. The callbacks are thin wrappers around
// geometry/quadric.h. Internal to accel/embree, the only module that includes Embree.
#pragma once

#include <embree3/rtcore.h>

#include "core/ray.h"
#include "geometry/quadric.h"
#include "scene/scene.h"

namespace kiln {

// The intersect context kiln passes to rtcIntersect1/rtcOccluded1 and the occlusion packets.
// Embree hands user geometry the ray already moved to object space in float; the quadric callbacks
// instead re-transform the original world ray in double (object_from_world of the instance Embree
// is visiting), so the hit does not carry float transform error and equals what a non-Embree
// backend computes. The world ray of an Embree ray is world_rays[its id]: a single ray has id 0,
// a packet's lanes carry their index into the rays the packet was filled from.
struct kiln_intersect_context {
  RTCIntersectContext embree;  // must stay first: Embree sees a pointer to this member
  const scene* world = nullptr;
  const ray* world_rays = nullptr;
};

// Builds the single-primitive user-geometry scene of one quadric definition, prepared once for
// its callbacks. `q` (and the quadric it names) must outlive it.
RTCScene build_quadric_scene(RTCDevice device, const prepared_quadric& q);

}  // namespace kiln
