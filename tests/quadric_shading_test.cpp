// Shading on quadrics through the real pipeline (Embree backend, Whitted shading, tile renderer):
// a quadric sphere casts a shadow, a lat-long texture on a sphere reads upright (the texel at a
// known UV), a normal map tilts toward the image top on plain and mirrored placements, and the
// depth AOV of a quadric is the analytic distance.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "accel/embree/embree_accelerator.h"
#include "geometry/quadric_test_util.h"
#include "render/tile_renderer.h"
#include "shade/normal_mapping.h"
#include "shade/whitted.h"
#include "support/shadow_probe.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

material diffuse() {
  material m;
  m.metallic_factor = 0.0f;
  m.specular_factor = 0.0f;
  return m;
}

void place_quadric(scene& s, const quadric& q, const dmat4& world_from_object, uint32_t material) {
  s.quadrics.push_back(q);
  instance inst;
  inst.kind = shape_kind::quadric;
  inst.shape = uint32_t(s.quadrics.size() - 1);
  inst.material = material;
  inst.world_from_object = world_from_object;
  finish_instance_transform(inst);
  s.instances.push_back(inst);
}

// The probe's covered floor point (0.5, 0, 0) sees the light at (0, 0, 4) along a segment whose
// midpoint is (0.25, 0, 2); the open point's segment passes 0.5 from there.
TEST(quadric_shading, a_sphere_on_the_light_path_casts_a_full_shadow_and_one_beside_it_none) {
  for (const dvec3& centre : {dvec3(0.25, 0, 2), dvec3(3, 0, 2)}) {
    scene s;
    s.materials = {diffuse()};
    // An ellipsoid (scaled unit sphere), 0.3 across the light path.
    place_quadric(s, testing::make_sphere(1.0),
                  glm::scale(glm::translate(dmat4(1.0), centre), dvec3(0.3, 0.4, 0.2)), 0);
    const vec3 through = testing::light_through_cover(s);
    const float expected = centre.x < 1.0 ? 0.0f : 1.0f;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(through[c], expected, 1e-6f) << "centre x " << centre.x;
  }
}

// An unlit sphere with a 4×2 nearest-filtered texture, every texel a different colour: a ray
// that hits at azimuth φ and latitude λ sees the texel at u = φ/2π, v = (90° − λ)/180°, so
// northern latitudes read the image's top row (glTF's v = 0) and the texture is upright.
TEST(quadric_shading, a_lat_long_texture_on_a_sphere_shows_the_texel_at_the_hit_uv) {
  scene s;
  image img;
  img.width = 4;
  img.height = 2;
  for (int i = 0; i < 8; ++i) {  // texel i = (i & 1, i & 2, i & 4) in {0, 255}: sRGB-exact
    img.texels8.insert(img.texels8.end(),
                       {uint8_t(i & 1 ? 255 : 0), uint8_t(i & 2 ? 255 : 0), uint8_t(i & 4 ? 255 : 0), 255});
  }
  s.images.push_back(img);
  texture tex;
  tex.sampling = {wrap_mode::repeat, wrap_mode::clamp_to_edge, filter_mode::nearest};
  s.textures.push_back(tex);
  material m;
  m.unlit = true;
  m.base_color_texture.texture = 0;
  s.materials = {m};
  place_quadric(s, testing::make_sphere(1.0), glm::translate(dmat4(1.0), dvec3(0, 0, -10)), 0);
  embree_accelerator accel(s);
  shading_options options;
  options.max_depth = 0;
  shading_context ctx{s, accel, options, false};

  struct probe {
    double azimuth_deg, latitude_deg;
    int column, row;
  };
  for (const probe& p : {probe{45, 30, 0, 0}, probe{135, -30, 1, 1}, probe{225, -60, 2, 1},
                         probe{315, 60, 3, 0}, probe{100, 10, 1, 0}}) {
    const double phi = glm::radians(p.azimuth_deg), lat = glm::radians(p.latitude_deg);
    const dvec3 on_sphere(std::cos(lat) * std::cos(phi), std::cos(lat) * std::sin(phi), std::sin(lat));
    const dvec3 centre(0, 0, -10);
    // From outside along the normal, straight at the point.
    const ray r = testing::make_ray(vec3(centre + 3.0 * on_sphere), vec3(-on_sphere));
    ray_counts counts;
    const vec3 colour = trace_radiance(ctx, r, path_state{}, counts);
    const int texel = p.row * 4 + p.column;
    const vec3 expected(texel & 1 ? 1.0f : 0.0f, texel & 2 ? 1.0f : 0.0f, texel & 4 ? 1.0f : 0.0f);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(colour[c], expected[c], 1e-6f)
          << "azimuth " << p.azimuth_deg << ", latitude " << p.latitude_deg;
    }
  }
}

// A normal map whose texels tilt the normal 45° toward the image's top (+Y, green) tilts a quadric's
// shading normal toward +z (north on the sphere, up the cylinder and the outside of the torus),
// also on mirrored instances: the tangent frame's handedness is right for every placement.
TEST(quadric_shading, a_normal_map_tilts_quadric_normals_toward_the_image_top_also_when_mirrored) {
  const std::vector<quadric> shapes = {testing::make_sphere(1.0),
                                       testing::make_axial(quadric_kind::cylinder, 1.0, -1.0, 1.0, true),
                                       testing::make_torus(0.7, 0.3)};
  for (const quadric& q : shapes) {
    for (double mirror : {1.0, -1.0}) {
      scene s;
      image img;
      img.width = img.height = 1;
      img.texels8 = {128, 218, 218, 255};  // tangent-space (0.004, 0.71, 0.71)
      s.images.push_back(img);
      s.textures.emplace_back();
      material m = diffuse();
      m.normal_texture.texture = 0;
      s.materials = {m};
      place_quadric(s, q, glm::scale(dmat4(1.0), dvec3(mirror, 1.0, 1.0)), 0);
      embree_accelerator accel(s);
      for (double azimuth : {0.3, 2.0, 4.0}) {
        const vec3 outward(float(std::cos(azimuth)), float(std::sin(azimuth)), 0.0f);
        const auto h = accel.intersect(testing::make_ray(5.0f * outward, -outward));
        ASSERT_TRUE(h.has_value());
        surface_point sp = make_surface_point(s, *h, testing::make_ray(5.0f * outward, -outward));
        apply_normal_map(s, m, material_inputs_at(sp), sp);
        EXPECT_NEAR(sp.shading_normal.z, std::sqrt(0.5f), 0.01f)
            << "kind " << int(q.kind) << (mirror < 0.0 ? " mirrored" : "") << ", azimuth " << azimuth;
        EXPECT_NEAR(glm::dot(sp.shading_normal, sp.geometric_normal), std::sqrt(0.5f), 0.01f);
      }
    }
  }
}

// The centre pixel's depth (ray distance) is the distance from the eye to the nearest point of
// the primitive on the optical axis: D − r for a sphere and for a cylinder seen side-on, D − h
// for a cone seen from above its apex.
TEST(quadric_shading, depth_aov_of_the_centre_pixel_is_the_analytic_distance) {
  struct shape {
    quadric q;
    dmat4 world_from_object;
    double expected;
  };
  const double distance = 7.0;
  const std::vector<shape> shapes = {
      {testing::make_sphere(1.0), dmat4(1.0), distance - 1.0},
      {testing::make_sphere(1.0), glm::scale(dmat4(1.0), dvec3(1.0, 1.0, 2.5)), distance - 2.5},  // ellipsoid
      {testing::make_axial(quadric_kind::cylinder, 0.5, -1.0, 1.0, true),
       glm::rotate(dmat4(1.0), glm::radians(90.0), dvec3(1, 0, 0)), distance - 0.5},
      {testing::make_axial(quadric_kind::cone, 1.0, 0.0, 2.0, true, 2.0), dmat4(1.0), distance - 2.0},
      {testing::make_torus(1.0, 0.3), glm::translate(dmat4(1.0), dvec3(-1, 0, 0)), distance - 0.3},
  };
  for (const shape& sh : shapes) {
    scene s;
    s.materials = {diffuse()};
    place_quadric(s, sh.q, sh.world_from_object, 0);
    light l;
    l.position = dvec3(0, 0, 10);
    s.lights.push_back(l);
    embree_accelerator accel(s);
    const int size = 33;  // odd: the centre pixel's ray is the optical axis
    const view_camera cam =
        make_look_at_camera(dvec3(0, 0, distance), dvec3(0.0), dvec3(0, 1, 0), 20.0, size, size);
    render_settings settings;
    settings.threads = 1;
    const film image = render_image(s, accel, cam, settings);
    const float depth = image.depth[image.index(size / 2, size / 2)];
    EXPECT_NEAR(depth, sh.expected, 1e-5 * distance) << "kind " << int(sh.q.kind);
  }
}

}  // namespace
}  // namespace kiln
