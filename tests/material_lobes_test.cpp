// The material extensions' lobes on the lobe sphere (and disk) under one directional light: every
// ray's radiance equals f(v, l) · E · |cos θ| of the specifications' closed form
// (support/gltf_brdf_reference.h, in double), through the loader, Embree and Whitted shading.
// Factors and textures both feed each lobe; textures are constant images, so each is one number.
#include "shade/material_lobes.h"

#include <gtest/gtest.h>

#include "support/gltf_brdf_reference.h"
#include "support/lobe_sphere.h"

namespace kiln {
namespace {

using nlohmann::json;
using testing::reference_material;

// Traces setup and compares every ray against reference (whose anisotropy direction, when set, is
// the tangent turned by `rotation` toward the bitangent cross(n, t)). tolerance: relative.
// coat_texel: the clearcoat normal map's tangent-space normal (2 · texel − 1), when it has one.
void expect_lobe(const testing::lobe_sphere& setup, reference_material reference, const std::string& name,
                 double tolerance = 1e-4, double rotation = 0.0, const dvec3* coat_texel = nullptr) {
  int lit = 0;
  for (const testing::lobe_ray& r : testing::trace_lobe_sphere(setup, name)) {
    const double cos_l = glm::dot(r.normal, r.to_light);
    if (reference.anisotropy > 0.0)
      reference.anisotropy_direction =
          std::cos(rotation) * r.tangent + std::sin(rotation) * glm::cross(r.normal, r.tangent);
    if (coat_texel)
      reference.clearcoat_normal =
          glm::normalize(r.tangent * coat_texel->x + glm::cross(r.normal, r.tangent) * coat_texel->y +
                         r.normal * coat_texel->z);
    const dvec3 expected = testing::reference_brdf(reference, r.normal, r.to_viewer, r.to_light) *
                           setup.illuminance * std::abs(cos_l);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(r.radiance[c], expected[c], tolerance * expected[c] + 1e-6)
          << name << ": channel " << c << " at normal " << r.normal.x << "," << r.normal.y << ","
          << r.normal.z;
    if (expected != dvec3(0.0)) ++lit;
  }
  EXPECT_GT(lit, setup.grid * setup.grid / 4) << name;  // most of the disk is lit: not an empty image
}

json pbr(const dvec3& base, double metallic, double roughness) {
  return {{"baseColorFactor", {base.r, base.g, base.b, 1.0}},
          {"metallicFactor", metallic},
          {"roughnessFactor", roughness}};
}

reference_material reference_of(const dvec3& base, double metallic, double roughness) {
  reference_material m;
  m.base = base;
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

TEST(material_lobes, specular_factors_and_textures_weight_and_tint_the_dielectric_fresnel) {
  testing::lobe_sphere setup;
  setup.textures = {{255, 255, 255, 128}, {200, 100, 50, 255}};
  setup.extensions = {"KHR_materials_specular", "KHR_materials_ior"};
  setup.material = {{"pbrMetallicRoughness", pbr({0.5, 0.4, 0.3}, 0.0, 0.45)},
                    {"extensions",
                     {{"KHR_materials_specular",
                       {{"specularFactor", 0.8},
                        {"specularTexture", {{"index", 0}}},
                        {"specularColorFactor", {1.0, 0.9, 0.8}},
                        {"specularColorTexture", {{"index", 1}}}}},
                      {"KHR_materials_ior", {{"ior", 1.7}}}}}};
  reference_material m = reference_of({0.5, 0.4, 0.3}, 0.0, 0.45);
  m.ior = 1.7;
  m.specular = 0.8 * 128.0 / 255.0;
  m.specular_color = dvec3(1.0, 0.9, 0.8) *
                     dvec3(testing::srgb_decode8(200), testing::srgb_decode8(100), testing::srgb_decode8(50));
  expect_lobe(setup, m, "specular");
}

TEST(material_lobes, clearcoat_layers_a_fresnel_weighted_ggx_coat_over_the_base) {
  testing::lobe_sphere setup;
  setup.textures = {{204, 0, 0, 255}, {0, 153, 0, 255}};
  setup.extensions = {"KHR_materials_clearcoat"};
  setup.material = {{"pbrMetallicRoughness", pbr({0.7, 0.1, 0.1}, 0.0, 0.6)},
                    {"extensions",
                     {{"KHR_materials_clearcoat",
                       {{"clearcoatFactor", 1.0},
                        {"clearcoatTexture", {{"index", 0}}},
                        {"clearcoatRoughnessFactor", 0.5},
                        {"clearcoatRoughnessTexture", {{"index", 1}}}}}}}};
  reference_material m = reference_of({0.7, 0.1, 0.1}, 0.0, 0.6);
  m.clearcoat = 204.0 / 255.0;
  m.clearcoat_roughness = 0.5 * 153.0 / 255.0;
  expect_lobe(setup, m, "clearcoat");
}

TEST(material_lobes, the_clearcoat_normal_map_tilts_the_coat_alone) {
  testing::lobe_sphere setup;
  setup.textures = {{191, 128, 230, 255}};
  setup.min_radius = 0.15;  // the sphere's tangent turns about its pole
  setup.max_radius = 0.8;   // the tilted coat normal stays facing the viewer
  setup.extensions = {"KHR_materials_clearcoat"};
  setup.material = {{"pbrMetallicRoughness", pbr({0.2, 0.5, 0.8}, 0.0, 0.7)},
                    {"extensions",
                     {{"KHR_materials_clearcoat",
                       {{"clearcoatFactor", 1.0},
                        {"clearcoatRoughnessFactor", 0.3},
                        {"clearcoatNormalTexture", {{"index", 0}}}}}}}};
  reference_material m = reference_of({0.2, 0.5, 0.8}, 0.0, 0.7);
  m.clearcoat = 1.0;
  m.clearcoat_roughness = 0.3;
  const dvec3 texel = dvec3(191.0, 128.0, 230.0) / 255.0 * 2.0 - 1.0;
  expect_lobe(setup, m, "clearcoat_normal", 1e-3, 0.0, &texel);
}

TEST(material_lobes, clearcoat_over_metal_without_textures) {
  testing::lobe_sphere setup;
  setup.extensions = {"KHR_materials_clearcoat"};
  setup.material = {
      {"pbrMetallicRoughness", pbr({0.9, 0.6, 0.2}, 1.0, 0.5)},
      {"extensions",
       {{"KHR_materials_clearcoat", {{"clearcoatFactor", 0.7}, {"clearcoatRoughnessFactor", 0.2}}}}}};
  reference_material m = reference_of({0.9, 0.6, 0.2}, 1.0, 0.5);
  m.clearcoat = 0.7;
  m.clearcoat_roughness = 0.2;
  expect_lobe(setup, m, "clearcoat_metal");
}

TEST(material_lobes, sheen_adds_charlie_sheen_over_the_albedo_scaled_base) {
  testing::lobe_sphere setup;
  setup.grid = 20;  // the reference integrates the albedo twice per ray
  setup.textures = {{230, 128, 77, 255}, {0, 0, 0, 204}};
  setup.extensions = {"KHR_materials_sheen"};
  setup.material = {{"pbrMetallicRoughness", pbr({0.2, 0.3, 0.6}, 0.0, 0.7)},
                    {"extensions",
                     {{"KHR_materials_sheen",
                       {{"sheenColorFactor", {1.0, 0.9, 0.8}},
                        {"sheenColorTexture", {{"index", 0}}},
                        {"sheenRoughnessFactor", 0.75},
                        {"sheenRoughnessTexture", {{"index", 1}}}}}}}};
  reference_material m = reference_of({0.2, 0.3, 0.6}, 0.0, 0.7);
  m.sheen_color = dvec3(1.0, 0.9, 0.8) *
                  dvec3(testing::srgb_decode8(230), testing::srgb_decode8(128), testing::srgb_decode8(77));
  m.sheen_roughness = 0.75 * 204.0 / 255.0;
  // kiln reads the albedo from a 32 × 32 table integrated at first use; the reference integrates
  // it afresh per ray. Their difference, not float, sets the tolerance.
  expect_lobe(setup, m, "sheen", 3e-3);
}

TEST(material_lobes, sheen_albedo_table_matches_an_independent_integration) {
  // kiln's table (integrated over the half vector, read bilinearly) against the quadrature over the
  // light direction, across roughness and view angle, off the table's grid points too.
  for (double r : {0.1, 0.23, 0.5, 0.77, 1.0})
    for (double mu : {0.05, 0.21, 0.5, 0.83, 1.0}) {
      const double e = testing::reference_sheen_albedo(mu, r);
      EXPECT_NEAR(sheen_directional_albedo(float(mu), float(r)), e, 2e-3 + 1e-2 * e)
          << "r " << r << " mu " << mu;
      EXPECT_GT(e, 0.0);
    }
}

void expect_iridescent(double metallic, const std::string& name) {
  testing::lobe_sphere setup;
  setup.textures = {{0, 128, 0, 255}};
  setup.extensions = {"KHR_materials_iridescence"};
  setup.material = {{"pbrMetallicRoughness", pbr({0.8, 0.7, 0.6}, metallic, 0.35)},
                    {"extensions",
                     {{"KHR_materials_iridescence",
                       {{"iridescenceFactor", 0.9},
                        {"iridescenceIor", 1.6},
                        {"iridescenceThicknessMinimum", 200.0},
                        {"iridescenceThicknessMaximum", 500.0},
                        {"iridescenceThicknessTexture", {{"index", 0}}}}}}}};
  reference_material m = reference_of({0.8, 0.7, 0.6}, metallic, 0.35);
  m.iridescence = 0.9;
  m.iridescence_ior = 1.6;
  m.iridescence_thickness = 200.0 + 300.0 * 128.0 / 255.0;
  expect_lobe(setup, m, name, 3e-4);
}

TEST(material_lobes, iridescence_replaces_schlick_by_the_thin_film_fresnel_on_a_dielectric) {
  expect_iridescent(0.0, "iridescence_dielectric");
}
TEST(material_lobes, iridescence_replaces_schlick_by_the_thin_film_fresnel_on_a_metal) {
  expect_iridescent(1.0, "iridescence_metal");
}

TEST(material_lobes, thin_film_fresnel_has_no_film_at_zero_thickness_and_colours_at_400nm) {
  const dvec3 f0(0.04);
  // Without a film the reflectance is the base's Schlick Fresnel.
  const dvec3 bare = testing::reference_iridescence_fresnel(1.3, 1.0, 1e-9, f0);
  EXPECT_NEAR(bare.g, 0.04, 0.01);
  // A 400 nm film of ior 1.3 over glass tints the reflection: the channels part.
  const dvec3 film = testing::reference_iridescence_fresnel(1.3, 1.0, 400.0, f0);
  EXPECT_GT(std::max({film.r, film.g, film.b}) - std::min({film.r, film.g, film.b}), 0.01);
}

TEST(material_lobes, the_largest_values_the_loader_takes_shade_finite) {
  // Every lobe member at the top of its range (float's largest where the spec sets no maximum):
  // the film's path length and the lobes' weights stay finite, so no sample is discarded.
  testing::lobe_sphere setup;
  const double big = 3.4e38;
  setup.extensions = {"KHR_materials_iridescence", "KHR_materials_sheen", "KHR_materials_clearcoat",
                      "KHR_materials_anisotropy"};
  setup.material = {
      {"pbrMetallicRoughness", pbr({0.5, 0.5, 0.5}, 0.5, 0.5)},
      {"extensions",
       {{"KHR_materials_iridescence",
         {{"iridescenceFactor", 1.0},
          {"iridescenceIor", big},
          {"iridescenceThicknessMinimum", big},
          {"iridescenceThicknessMaximum", big}}},
        {"KHR_materials_sheen", {{"sheenColorFactor", {big, big, big}}, {"sheenRoughnessFactor", 1.0}}},
        {"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}, {"clearcoatRoughnessFactor", 1.0}}},
        {"KHR_materials_anisotropy", {{"anisotropyStrength", 1.0}, {"anisotropyRotation", 1e6}}}}}};
  int rays = 0;
  for (const testing::lobe_ray& r : testing::trace_lobe_sphere(setup, "largest_values")) {
    for (int c = 0; c < 3; ++c)
      ASSERT_TRUE(std::isfinite(r.radiance[c]) && r.radiance[c] >= 0.0f) << r.radiance[c];
    ++rays;
  }
  EXPECT_GT(rays, 1000);
}

TEST(material_lobes, anisotropy_stretches_the_ggx_lobe_along_the_rotated_tangent) {
  testing::lobe_sphere setup;
  setup.textures = {{255, 128, 204, 255}};  // direction (1, 0.004) in tangent space, strength 0.8
  setup.min_radius = 0.15;                  // the sphere's tangent turns about its pole
  setup.extensions = {"KHR_materials_anisotropy"};
  setup.material = {{"pbrMetallicRoughness", pbr({0.9, 0.8, 0.7}, 1.0, 0.4)},
                    {"extensions",
                     {{"KHR_materials_anisotropy",
                       {{"anisotropyStrength", 0.75},
                        {"anisotropyRotation", 0.6},
                        {"anisotropyTexture", {{"index", 0}}}}}}}};
  reference_material m = reference_of({0.9, 0.8, 0.7}, 1.0, 0.4);
  m.anisotropy = 0.75 * 204.0 / 255.0;
  const double texture_angle = std::atan2(128.0 / 255.0 * 2.0 - 1.0, 1.0);
  expect_lobe(setup, m, "anisotropy", 1e-3, 0.6 + texture_angle);
}

reference_material translucent() {
  reference_material m = reference_of({0.2, 0.8, 0.2}, 0.0, 0.5);
  m.diffuse_transmission = 0.7 * 153.0 / 255.0;
  m.diffuse_transmission_color =
      dvec3(0.9, 0.6, 0.3) *
      dvec3(testing::srgb_decode8(255), testing::srgb_decode8(200), testing::srgb_decode8(255));
  return m;
}

testing::lobe_sphere translucent_disk(const dvec3& to_light) {
  testing::lobe_sphere setup;
  setup.shape = "disk";
  setup.to_light = glm::normalize(to_light);
  setup.textures = {{0, 0, 0, 153}, {255, 200, 255, 255}};
  setup.extensions = {"KHR_materials_diffuse_transmission"};
  setup.material = {{"pbrMetallicRoughness", pbr({0.2, 0.8, 0.2}, 0.0, 0.5)},
                    {"extensions",
                     {{"KHR_materials_diffuse_transmission",
                       {{"diffuseTransmissionFactor", 0.7},
                        {"diffuseTransmissionTexture", {{"index", 0}}},
                        {"diffuseTransmissionColorFactor", {0.9, 0.6, 0.3}},
                        {"diffuseTransmissionColorTexture", {{"index", 1}}}}}}}};
  return setup;
}

TEST(material_lobes, diffuse_transmission_lets_a_light_behind_a_thin_surface_through) {
  expect_lobe(translucent_disk({0.3, 0.4, -1.0}), translucent(), "diffuse_transmission_behind");
}

TEST(material_lobes, diffuse_transmission_takes_its_share_from_the_front_diffuse_lobe) {
  expect_lobe(translucent_disk({0.3, 0.4, 1.0}), translucent(), "diffuse_transmission_front");
}

TEST(material_lobes, every_lobe_together_composes_as_the_specifications_layer_them) {
  testing::lobe_sphere setup;
  setup.extensions = {"KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_iridescence",
                      "KHR_materials_specular"};
  setup.material = {
      {"pbrMetallicRoughness", pbr({0.6, 0.3, 0.5}, 0.3, 0.55)},
      {"extensions",
       {{"KHR_materials_clearcoat", {{"clearcoatFactor", 0.5}, {"clearcoatRoughnessFactor", 0.25}}},
        {"KHR_materials_sheen", {{"sheenColorFactor", {0.4, 0.5, 0.6}}, {"sheenRoughnessFactor", 0.5}}},
        {"KHR_materials_iridescence", {{"iridescenceFactor", 0.5}}},
        {"KHR_materials_specular", {{"specularFactor", 0.9}, {"specularColorFactor", {0.9, 1.0, 0.8}}}}}}};
  reference_material m = reference_of({0.6, 0.3, 0.5}, 0.3, 0.55);
  m.clearcoat = 0.5;
  m.clearcoat_roughness = 0.25;
  m.sheen_color = {0.4, 0.5, 0.6};
  m.sheen_roughness = 0.5;
  m.iridescence = 0.5;
  m.specular = 0.9;
  m.specular_color = {0.9, 1.0, 0.8};
  setup.grid = 20;  // the reference integrates the sheen albedo twice per ray
  expect_lobe(setup, m, "all_lobes", 3e-3);
}

}  // namespace
}  // namespace kiln
