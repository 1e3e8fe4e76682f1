// The demo scene (a room with a mirror, glass, quadrics and a textured floor) rendered at scene scales 1e-3,
// 1 and 1e4, moved far from the origin as well: secondary rays (shadow and mirror) must never re-hit the
// surface they leave, so every scaled image equals the unit-scale one except for rounding at edges. Shadow
// acne or a self-reflecting mirror darkens a large share of the pixels instead.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "render/tile_renderer.h"
#include "render/view_camera.h"

namespace kiln {
namespace {

const std::string demo_scene = std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf";

// Scales the whole scene about the origin and then moves it by `shift`; point and spot lights get
// intensity × scale² so the irradiance at every scaled point is unchanged, and the lengths of
// KHR_materials_volume (absorption per world unit in glass) scale with the scene.
void scale_scene(scene& s, double scale, const dvec3& shift) {
  const dmat4 world_from_world = glm::translate(dmat4(1.0), shift) * glm::scale(dmat4(1.0), dvec3(scale));
  for (instance& inst : s.instances) {
    inst.world_from_object = world_from_world * inst.world_from_object;
    finish_instance_transform(inst);
  }
  for (light& l : s.lights) {
    l.position = dvec3(world_from_world * dvec4(l.position, 1.0));
    if (l.kind != light_kind::directional) l.intensity = float(double(l.intensity) * scale * scale);
    l.range = float(double(l.range) * scale);
  }
  for (camera& c : s.cameras) c.world_from_camera = world_from_world * c.world_from_camera;
  for (material& m : s.materials) {
    m.attenuation_distance = float(double(m.attenuation_distance) * scale);
    m.thickness_factor = float(double(m.thickness_factor) * scale);
  }
}

film render_demo(double scale, const dvec3& shift) {
  scene s = load_gltf(demo_scene);
  scale_scene(s, scale, shift);
  embree_accelerator accel(s);
  view_camera cam = make_gltf_camera(s.cameras.at(0), 96, 72);
  render_settings settings;
  settings.threads = 2;
  settings.aovs.set(aov::ids);  // for on_edge
  return render_image(s, accel, cam, settings);
}

// True where the reference pixel sits on a geometric edge: a neighbour sees another normal (a
// crease where two walls meet), a much different depth (a silhouette) or another instance (the
// mirror slab 2 cm before the back wall faces the same way at nearly the same depth). A ray
// through an edge may hit either side after rounding, so those pixels legitimately change with
// scale.
bool on_edge(const film& f, int x, int y) {
  const size_t centre = f.index(x, y);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= f.width || ny >= f.height) continue;
      const size_t n = f.index(nx, ny);
      if (std::isinf(f.depth[centre]) && std::isinf(f.depth[n])) continue;  // both background
      if (glm::dot(f.vec3_layer(aov::normal)[centre], f.vec3_layer(aov::normal)[n]) < 0.95f) return true;
      if (f.ids[centre].z != f.ids[n].z) return true;
      if (std::isinf(f.depth[centre]) != std::isinf(f.depth[n]) ||
          std::abs(f.depth[centre] - f.depth[n]) > 0.25f * f.depth[centre])
        return true;
    }
  return false;
}

struct image_difference {
  double interior_share = 0.0;   // share of pixels away from edges
  double differing_share = 0.0;  // share of those interior pixels off by more than 1%
};

// Compares colour away from geometric edges: 1% relative, with an absolute floor for dark pixels.
image_difference compare_interiors(const film& reference, const film& image) {
  size_t interior = 0, differing = 0;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      if (on_edge(reference, x, y)) continue;
      ++interior;
      const vec4 a = reference.color[reference.index(x, y)], b = image.color[image.index(x, y)];
      for (int c = 0; c < 3; ++c)
        if (std::abs(a[c] - b[c]) > 1e-2f * std::max(std::abs(a[c]), 1e-2f)) {
          ++differing;
          break;
        }
    }
  image_difference d;
  d.interior_share = double(interior) / double(reference.color.size());
  d.differing_share = interior ? double(differing) / double(interior) : 1.0;
  return d;
}

TEST(demo_scene_scale, secondary_rays_never_rehit_their_surface_at_any_scale) {
  const film unit = render_demo(1.0, dvec3(0.0));
  // The reference is lit and has a visible mirror: a black image would pass trivially otherwise.
  double sum = 0.0;
  for (const vec4& c : unit.color) sum += c.x + c.y + c.z;
  ASSERT_GT(sum / double(unit.color.size()), 0.05);
  for (double scale : {1e-3, 1e4}) {
    for (const dvec3& shift : {dvec3(0.0), dvec3(3.7, -2.1, 5.3) * scale * 10.0}) {
      const film scaled = render_demo(scale, shift);
      const image_difference d = compare_interiors(unit, scaled);
      EXPECT_GT(d.interior_share, 0.7);  // edges are a small part of the image
      // Moved 10 scene sizes away, world-space float hit points round coarser; seen in the mirror
      // through the glass, whose refraction magnifies that, one or two pixels of about 6,000
      // ((38,40) and (34,48)) change by 1.0-1.1% in the dark red channel. Shadow acne or
      // self-reflection would change thousands. Scaled about the origin, nothing may change.
      const bool shifted = shift != dvec3(0.0);
      EXPECT_LE(d.differing_share, shifted ? 3.0 / 6000.0 : 0.0)
          << "scale " << scale << ", shift " << shift.x;
    }
  }
}

}  // namespace
}  // namespace kiln
