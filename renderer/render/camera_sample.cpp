#include "render/camera_sample.h"

#include "shade/environment.h"

namespace kiln {

camera_sample trace_camera_sample(const shading_context& ctx, const view_camera& cam, bool show_background,
                                  double px, double py, const ray_cone& cone, ray_counts& counts) {
  camera_sample s;
  const ray start = generate_camera_ray(cam, px, py);
  ray r = start;  // find_visible_hit moves the origin past culled back faces
  ++counts.camera;
  std::optional<hit> h = find_visible_hit(ctx, r, counts);
  if (!h) {
    if (show_background) s.rgba = vec4(environment_radiance(ctx.world, r.direction), 1.0f);
    return s;
  }
  const ray_cone at_hit = cone_at(cone, distance_to_hit(start, r, *h));
  surface_point sp = make_surface_point(ctx.world, *h, r, at_hit.width);
  s.rgba = vec4(shade_surface(ctx, r, sp, 0, 1.0f, counts, medium_stack{}, at_hit), 1.0f);
  s.depth = distance_to_hit(start, r, *h);  // from the camera, also behind culled back faces
  s.normal = sp.shading_normal;
  s.instance = h->instance_id;
  return s;
}

}  // namespace kiln
