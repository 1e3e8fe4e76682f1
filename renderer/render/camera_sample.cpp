#include "render/camera_sample.h"

#include "shade/environment.h"

namespace kiln {

camera_sample trace_camera_sample(const shading_context& ctx, const view_camera& cam, bool show_background,
                                  double px, double py, ray_counts& counts) {
  camera_sample s;
  ray r = generate_camera_ray(cam, px, py);
  ++counts.camera;
  std::optional<hit> h = find_visible_hit(ctx, r, counts);
  if (!h) {
    if (show_background) s.rgba = vec4(environment_radiance(ctx.world, r.direction), 1.0f);
    return s;
  }
  surface_point sp = make_surface_point(ctx.world, *h, r);
  s.rgba = vec4(shade_surface(ctx, r, sp, 0, 1.0f, counts), 1.0f);
  s.depth = h->t;
  s.normal = sp.shading_normal;
  s.instance = h->instance_id;
  return s;
}

}  // namespace kiln
