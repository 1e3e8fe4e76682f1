#include "render/view_range.h"

#include "core/error.h"
#include "core/message_text.h"
#include "scene/coordinate_range.h"

namespace kiln {

namespace {

// The camera's own ray origins: the eye, and the corners of an orthographic window.
bounds3 camera_origin_bounds(const view_camera& cam) {
  bounds3 b;
  b.extend(cam.eye);
  if (cam.kind == projection::orthographic)
    for (double x : {cam.left, cam.right_edge})
      for (double y : {cam.bottom, cam.top})
        b.extend(cam.eye + cam.distance * cam.view + x * cam.right + y * cam.up);
  return b;
}

std::string node_pointer(const scene& s, uint32_t node) {
  std::string where = "/nodes/" + std::to_string(node);
  if (node < s.node_names.size() && !s.node_names[node].empty()) where += " " + quoted(s.node_names[node]);
  return where;
}

}  // namespace

bounds3 ray_origin_bounds(const scene& s, const view_camera& cam) {
  bounds3 b = world_bounds(s);
  b.extend(camera_origin_bounds(cam));
  return b;
}

void check_view_range(const scene& s, const view_camera& cam, const std::string& camera_file,
                      const std::string& camera_location) {
  const double camera_reach = max_abs_coordinate(camera_origin_bounds(cam));
  if (!(camera_reach <= max_coordinate))
    throw input_error(camera_file, camera_location,
                      "camera rays start at " + format_coordinate(camera_reach) +
                          ", beyond kiln's coordinate limit of " + format_coordinate(max_coordinate));
  for (const instance& inst : s.instances) {
    const bounds3& object =
        inst.kind == shape_kind::quadric ? s.quadrics[inst.shape].bounds : s.meshes[inst.shape].bounds;
    const double reach = max_abs_coordinate(transform_bounds(inst.world_from_object, object));
    if (!(reach <= max_coordinate))
      throw input_error(s.source, node_pointer(s, inst.node),
                        "its shape reaches " + format_coordinate(reach) +
                            " in world space, beyond kiln's coordinate limit of " +
                            format_coordinate(max_coordinate));
  }
  const bounds3 origins = ray_origin_bounds(s, cam);
  for (const instance& inst : s.instances)
    if (auto problem = object_space_range_problem(inst, origins))
      throw input_error(s.source, node_pointer(s, inst.node), *problem);
}

}  // namespace kiln
