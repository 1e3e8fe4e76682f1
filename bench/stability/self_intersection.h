// Self-intersection experiments: secondary rays leaving a surface traced through Embree, once with
// a fixed epsilon and once with kiln's error-bound offset (core/float_bits.h offset_ray_origin
// with the hit's position error). Shared by bench/stability_study (CSV for chart 4) and
// tests/stability, which assert on the same numbers. Depends on accel/embree and geometry.
#pragma once

#include <cstdint>
#include <string>

namespace kiln::bench {

// How a secondary ray's origin leaves the surface. epsilon > 0: the textbook way, the hit point
// o + t·d moved by a fixed world-space epsilon along the geometric normal (to the side the ray
// leaves by). epsilon == 0: kiln's way, the hit point reconstructed with its rounding-error bound
// (triangle_hit_position / quadric_world_hit) and pushed off by offset_ray_origin.
struct offset_method {
  double epsilon = 0.0;
};
std::string method_name(const offset_method& m);  // "eps=1e-04" or "error_bound"

// plane: one large tilted triangle (the second surface a parallel triangle below it);
// sphere: an analytic sphere (the second surface a concentric sphere inside it). Both go through
// embree_accelerator with an instance transform of identity (triangles, vertices in world space)
// or translate·scale (the sphere).
enum class test_shape { plane, sphere };
const char* shape_name(test_shape s);

// Where the shape lies: size `scale` (the triangle's inradius, the sphere's radius), centred at
// `translation` along a fixed oblique direction.
struct placement {
  double scale = 1.0;
  double translation = 0.0;
};

// The relative gap of the thin-shell experiment: the second surface lies gap·scale behind the first.
constexpr double thin_gap = 4e-5;

struct self_intersection_result {
  int64_t shadow_rays = 0;    // primary hits on the lone surface, each casting one shadow ray
  int64_t acne = 0;           // shadow rays toward an unoccluded (directional) light that hit the surface
  int64_t gap_rays = 0;       // primary hits on the outer surface of the thin shell
  int64_t leaks = 0;          // continuation rays that did not stop at the inner surface (passed it)
  int64_t gap_self_hits = 0;  // continuation rays that re-hit the outer surface right where they left it
  double ns_per_shadow_ray = 0.0;  // hit-point reconstruction + offset + occlusion query
  double acne_rate() const { return shadow_rays ? double(acne) / double(shadow_rays) : 0.0; }
  double leak_rate() const { return gap_rays ? double(leaks) / double(gap_rays) : 0.0; }
};

// `rays` primary rays at random points and incidence (cos ≥ 0.5), from a fixed seed. Each hit on the
// lone surface casts a shadow ray toward a random light direction above the surface; each hit on the
// thin shell's outer surface continues straight on and must stop at the inner surface.
self_intersection_result measure_self_intersection(test_shape shape, const placement& where,
                                                   const offset_method& method, int rays, uint64_t seed);

}  // namespace kiln::bench
