// The shading point: what shading needs to know about a hit, reconstructed from the Scene and the
// backend-neutral Hit (barycentric interpolation of normals and UVs for triangles).
// Depends on scene, geometry and the ray types; never on a backend.
#pragma once

#include "core/ray.h"
#include "scene/scene.h"
#include "shade/texture_sampling.h"

namespace kiln {

// How fast a surface's normal turns per world unit (1 / radius of curvature) in its two principal
// directions: `major` where it turns fastest, tilting the normal toward `axis` (unit, world, across
// the normal; zero when the turn is the same every way), and `minor` at right angles to it. A
// cylinder turns at 1/r one way and not at all the other: a highlight widened by the larger turn
// in both directions would stretch along the cylinder and lose what runs off its ends.
struct surface_curvature {
  vec3 axis{0.0f};
  float major = 0.0f;
  float minor = 0.0f;

  bool operator==(const surface_curvature& o) const {
    return axis == o.axis && major == o.major && minor == o.minor;
  }
};

// The curvature of a patch whose unit normal changes by dn1, dn2 over the tangent displacements
// dp1, dp2 (a triangle's edges and the differences of its vertex normals, or any two independent
// steps), the normal taken as n (unit): the map from displacement to normal change in the tangent
// plane, by its singular values and the direction of its largest. Zero when dp1, dp2 are parallel.
surface_curvature curvature_from_differentials(const dvec3& n, const dvec3& dp1, const dvec3& dp2,
                                               const dvec3& dn1, const dvec3& dn2);

struct surface_point {
  vec3 position{0.0f};          // world space
  vec3 position_error{0.0f};    // per-axis bound on the rounding error of position
  vec3 geometric_normal{0.0f};  // unit, facing the incoming ray
  vec3 shading_normal{0.0f};    // unit, interpolated, on the same side as geometric_normal
  // The interpolated vertex normal before any normal map (geometric_normal without vertex normals
  // or on quadrics): the horizon of the smooth surface the mesh approximates, for the light test.
  vec3 smooth_normal{0.0f};
  // A point on that smooth surface above the flat triangle where it bulges outward (Hanika, "Hacking
  // the Shadow Terminator", Ray Tracing Gems II, ch. 4); position elsewhere. Shadow rays start
  // here, so a low-poly convex mesh does not shadow itself along its terminator.
  vec3 smooth_position{0.0f};
  // How fast the normal turns per world unit along the surface, for filtering sharp highlights
  // over the ray cone's footprint; zero when flat or not estimated (rough materials, no footprint).
  surface_curvature curvature;
  vec2 uv0{0.0f};
  vec2 uv1{0.0f};      // TEXCOORD_1 (TEXCOORD_0 when the mesh has none)
  vec4 color0{1.0f};   // COLOR_0, white when the mesh has none
  vec4 tangent{0.0f};  // world-space tangent (xyz, unnormalised) and handedness w; 0 when none
  // The ray cone's footprint in each UV set (before KHR_texture_transform); zero: no footprint.
  uv_footprint footprint0;
  uv_footprint footprint1;
  uint32_t material = 0;
  uint32_t instance = 0;   // the scene instance hit
  float time = 0.0f;       // the ray's time in the shutter: the rays leaving this point keep it
  bool front_face = true;  // the ray arrived on glTF's front side
};

// Materials whose roughness may fall below this (by factor or texture) get a curvature estimate (see
// surface_point); a rougher highlight is already wider than any footprint the estimate would widen
// it to.
constexpr float curvature_roughness_limit = 0.3f;

// What the shading point of a triangle hit takes from the triangle and its instance alone, the
// same for every hit on it: the unit vertex normals, and with a footprint the curvature, the world
// corners and each UV set's dP/du, dP/dv. Which of them a triangle needs depends on its mesh and
// material only; `footprint` says whether the footprint's part is filled.
struct triangle_constants {
  const instance* inst = nullptr;  // the key: the instance and the triangle's corner indices
  const uint32_t* idx = nullptr;
  bool footprint = false;
  dvec3 unit_normal[3];
  surface_curvature curvature;
  vec3 dp_du[2];  // per UV set (TEXCOORD_0, TEXCOORD_1)
  vec3 dp_dv[2];
};

// The triangle constants of the last few triangles one caller shaded: the samples of a tile, and
// the reflections they see, mostly hit the triangles their neighbours hit (86% of ToyCar's 16-spp
// shading points find theirs here; 80% with one memo per pixel, 90% with eight entries, which did
// not render faster). Keyed by addresses, so valid only while the scene does not change: a caller
// keeps one for one tile of one render. Entries are exactly what make_surface_point would
// compute, so results never depend on it.
struct triangle_memo {
  static constexpr int size = 4;
  triangle_constants entries[size];
  int next = 0;  // the entry a miss replaces
};

// Builds the shading point of a hit for the ray that found it. cone_width is the ray cone's width
// at the hit (world units, see shade/ray_cone.h); 0 leaves the UV footprints empty. memo (optional)
// keeps the triangle constants of still, undeformed triangles between calls.
surface_point make_surface_point(const scene& s, const hit& h, const ray& r, float cone_width = 0.0f,
                                 triangle_memo* memo = nullptr);

}  // namespace kiln
