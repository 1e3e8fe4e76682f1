// Analytic primitives (KILN_quadric): tight bounds, ray intersection and the surface at a hit
// (gradient normal, parametric UV, tangent, error bound), all in the primitive's canonical object
// space. Pure math in double precision with no Embree dependency: the Embree user-geometry
// callbacks and the grid backend call these same functions, so both return the same hit.
// Depends on core and scene only. See docs/quadrics.md for each kind's parameterisation.
#pragma once

#include <optional>

#include "core/ray.h"
#include "geometry/quadric_implicit.h"
#include "scene/scene.h"

namespace kiln {

using dvec2 = glm::dvec2;

// The sub-surface a hit lies on; carried in hit.primitive_id.
enum quadric_part : uint32_t { quadric_side = 0, quadric_cap_zmin = 1, quadric_cap_zmax = 2 };

// A ray parameter and the part it hit.
struct quadric_ray_hit {
  double t = 0.0;
  uint32_t part = quadric_side;
};

// Tight object-space bounds of a primitive (its clipped extent, caps included).
bounds3 quadric_bounds(const quadric& q);

// q.bounds where filled (the loader does), else quadric_bounds(q): per-ray code reads the stored
// box instead of recomputing it (the general quadric's costs a 3×3 inverse).
inline bounds3 stored_quadric_bounds(const quadric& q) {
  return q.bounds.empty() ? quadric_bounds(q) : q.bounds;
}

// The closest hit of o + t·d with t in (tmin, tmax), in object space and double precision, or
// empty. d need not be unit length; t is in units of d, so it is the world t of the same ray.
std::optional<quadric_ray_hit> intersect_quadric(const quadric& q, const dvec3& o, const dvec3& d,
                                                 double tmin, double tmax);

// What intersect_quadric derives from a primitive before solving, computed once per definition
// (per-ray code then reads it): the same values intersect_quadric(q, ...) computes on each call.
struct prepared_quadric {
  const quadric* shape = nullptr;  // must outlive this
  bounds3 bounds;                  // stored_quadric_bounds
  bounds3 padded;                  // bounds grown by 1e-9 of |lower| + |upper| per axis (slab test)
  dvec3 center{0.0};               // of bounds: the re-centring point
  implicit_form side;              // the side surface's F (zero for disk and torus)
  bool has_caps = false;           // axial kind with caps
  double cap_radius_zmin = 0.0, cap_radius_zmax = 0.0;
};
prepared_quadric prepare_quadric(const quadric& q);

// intersect_quadric on a prepared primitive. With any_hit it may return any hit in (tmin, tmax)
// instead of the closest (an occlusion query): it is empty exactly when the closest-hit form is.
std::optional<quadric_ray_hit> intersect_quadric(const prepared_quadric& p, const dvec3& o, const dvec3& d,
                                                 double tmin, double tmax, bool any_hit = false);

// The implicit function F of the side surface (F < 0 inside, F = 0 on the surface), and its gradient.
double quadric_implicit(const quadric& q, const dvec3& p);
dvec3 quadric_gradient(const quadric& q, const dvec3& p);

// The object-space surface at a hit.
struct quadric_surface {
  dvec3 point{0.0};   // projected onto the surface of `part`
  dvec3 normal{0.0};  // unit; normalised gradient of F (outward), or ±z on caps and disks
  dvec3 dpdu{0.0};    // unit tangent along u, perpendicular to normal
  dvec2 uv{0.0};      // parametric UV in [0,1]² (see docs/quadrics.md)
  // glTF tangent w: cross(normal, dpdu)·handedness points along −dp/dv, the image's "up" (glTF's
  // v grows downward), as the mesh tangent generator makes it.
  double handedness = 1.0;
  double error = 0.0;  // bound on the distance of `point` from the exact surface, object units
};

// The surface of `part` near an approximate hit point (e.g. o + t·d): the point is projected onto
// the surface in double precision, so its error no longer depends on how t was found.
quadric_surface quadric_surface_at(const quadric& q, uint32_t part, const dvec3& approx_point);

// A quadric hit in world space, with a per-axis bound on the position's rounding error.
struct quadric_world_point {
  vec3 point{0.0f};
  vec3 error{0.0f};
  vec3 normal{0.0f};        // unit, outward (gradient through the normal matrix, so mirrors keep it outward)
  vec3 tangent{0.0f};       // unit, world dp/du
  float handedness = 1.0f;  // glTF tangent w in world space (object w times the sign of det M)
  vec2 uv{0.0f};
};

// Reconstructs the hit of world ray r at parameter t on `part` of instance `inst` of q: the ray
// moves to object space in double, the point is projected onto the surface, then moves back.
quadric_world_point quadric_world_hit(const instance& inst, const quadric& q, const ray& r, float t,
                                      uint32_t part);

// The object-space surface at the hit of world ray r at t on `part` (the ray moved to object space
// in double, as the intersector does): computed once per hit, the functions below that take it
// give exactly what their (r, t) forms give without projecting the same point again.
quadric_surface quadric_surface_of_hit(const instance& inst, const quadric& q, const ray& r, float t,
                                       uint32_t part);

// quadric_world_hit from the object-space surface of the hit.
quadric_world_point quadric_world_point_of(const instance& inst, const quadric_surface& s);

// Only the world normal of quadric_world_hit (what an accelerator's hit record holds: culling
// needs it for every hit), without the uv, the tangent and the error bound, which shading
// computes for the hits it shades.
vec3 quadric_world_normal(const instance& inst, const quadric& q, const ray& r, float t, uint32_t part);

// World-space dP/du and dP/dv of the parametric UV at the same hit, by central differences of the
// UV along the surface (for texture footprints). False where the parameterisation is singular
// (poles, apex, disk centre).
bool quadric_world_uv_jacobian(const instance& inst, const quadric& q, const ray& r, float t, uint32_t part,
                               vec3& dp_du, vec3& dp_dv);
bool quadric_world_uv_jacobian(const instance& inst, const quadric& q, uint32_t part,
                               const quadric_surface& s, vec3& dp_du, vec3& dp_dv);

// A bound on the world-space curvature (1 / length) of the surface at the same hit: how fast the
// world normal turns per unit of world distance along the surface, the larger of two orthogonal
// tangents: in closed form from the constant Hessian on quadrics, by central differences on the
// torus. 0 where the surface is flat or the estimate is not finite.
float quadric_world_curvature(const instance& inst, const quadric& q, const ray& r, float t, uint32_t part);
float quadric_world_curvature(const instance& inst, const quadric& q, uint32_t part,
                              const quadric_surface& s);

// How the world normal turns at the same hit along two tangents across it: each tangent moves the
// point by step[i] and the unit normal by turn[i] (both world; in closed form on quadrics, over a
// central difference on the torus). shade/surface.h's curvature_from_differentials takes them to
// the two principal curvatures. Not valid where the surface is flat (caps, disks) or has no normal
// (the cone's apex).
struct quadric_normal_turns {
  bool valid = false;
  dvec3 normal{0.0};  // unit, world
  dvec3 step[2];
  dvec3 turn[2];
};
quadric_normal_turns quadric_world_normal_turns(const instance& inst, const quadric& q, uint32_t part,
                                                const quadric_surface& s);

// The torus quartic along a ray, in s = (t − t_c)·|d| from the ray's closest approach to the
// centre (coefficients[i] multiplies sⁱ; leading coefficient 1).
struct torus_ray_quartic {
  double coefficients[5] = {};
  double t_c = 0.0;
  double length = 1.0;  // |d|
};
torus_ray_quartic make_torus_quartic(double major_radius, double minor_radius, const dvec3& o,
                                     const dvec3& d);

// Torus: the closest root of the quartic in (tmin, tmax) (see torus.cpp).
std::optional<double> intersect_torus(double major_radius, double minor_radius, const dvec3& o,
                                      const dvec3& d, double tmin, double tmax);

// Radius of an axial kind's cross-section at height z (the cap radius at zmin/zmax).
double quadric_radius_at(const quadric& q, double z);

// Slab test of o + t·d against a box: narrows [tmin, tmax] to the part inside; false when empty.
bool clip_ray_to_box(const bounds3& box, const dvec3& o, const dvec3& d, double& tmin, double& tmax);

}  // namespace kiln
