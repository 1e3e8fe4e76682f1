#include "render/render_space.h"

namespace kiln {

void move_to_render_space(scene& s, view_camera& cam) {
  const dvec3 shift = cam.eye;
  for (instance& inst : s.instances) {
    // render_from_object = translate(-shift) · world_from_object: only the translation column
    // changes, and it is computed in double, so a placement 1e6 away keeps its sub-millimetre offset.
    inst.world_from_object[3] -= dvec4(shift, 0.0);
    finish_instance_transform(inst);
  }
  for (std::vector<dmat4>& steps : s.shutter.instance_steps)
    for (dmat4& step : steps) step[3] -= dvec4(shift, 0.0);
  for (light& l : s.lights) l.position -= shift;
  for (camera& c : s.cameras) c.world_from_camera[3] -= dvec4(shift, 0.0);
  cam.eye -= shift;
  s.render_origin += shift;
}

view_camera world_space_view(const view_camera& cam, const scene& s) {
  view_camera world = cam;
  world.eye += s.render_origin;
  return world;
}

}  // namespace kiln
