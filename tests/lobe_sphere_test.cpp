// The glTF metallic-roughness BRDF (specification, appendix B) on the lobe sphere under one
// directional light: every ray's radiance equals f(v, l) · E · cos θ from the closed form, computed
// here in double. The material extensions' image tests use the same sphere for their lobes.
#include "support/lobe_sphere.h"

#include <gtest/gtest.h>

namespace kiln {
namespace {

// glTF appendix B at one point: Lambert plus GGX with height-correlated Smith and Schlick's Fresnel,
// mixed by metallic; the dielectric F0 is 0.04.
dvec3 gltf_brdf(const dvec3& base, double metallic, double roughness, const dvec3& n, const dvec3& v,
                const dvec3& l) {
  const dvec3 h = glm::normalize(v + l);
  const double nl = glm::dot(n, l), nv = glm::dot(n, v), nh = glm::dot(n, h), vh = glm::dot(v, h);
  const double a2 = std::pow(roughness, 4.0);
  const double d = a2 / (pi * std::pow(nh * nh * (a2 - 1.0) + 1.0, 2.0));
  const double vis =
      0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
  const double schlick = std::pow(1.0 - vh, 5.0);
  const dvec3 f_metal = base + (dvec3(1.0) - base) * schlick;
  const double f_dielectric = 0.04 + 0.96 * schlick;
  const dvec3 dielectric = (1.0 - f_dielectric) * base / double(pi) + dvec3(f_dielectric * d * vis);
  const dvec3 metal = f_metal * (d * vis);
  return glm::mix(dielectric, metal, metallic);
}

void expect_gltf_brdf(double metallic, double roughness) {
  const dvec3 base(0.8, 0.3, 0.2);
  testing::lobe_sphere setup;
  setup.material = {{"pbrMetallicRoughness",
                     {{"baseColorFactor", {base.r, base.g, base.b, 1.0}},
                      {"metallicFactor", metallic},
                      {"roughnessFactor", roughness}}}};
  int lit = 0;
  for (const testing::lobe_ray& r : testing::trace_lobe_sphere(setup, "gltf_brdf")) {
    const double cos_l = glm::dot(r.normal, r.to_light);
    if (cos_l <= 0.0) {
      EXPECT_EQ(r.radiance, vec3(0.0f)) << "unlit side at normal " << r.normal.x << "," << r.normal.y;
      continue;
    }
    const dvec3 expected =
        gltf_brdf(base, metallic, roughness, r.normal, r.to_viewer, r.to_light) * setup.illuminance * cos_l;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(r.radiance[c], expected[c], 1e-4 * expected[c] + 1e-6)
          << "channel " << c << " at normal " << r.normal.x << "," << r.normal.y;
    ++lit;
  }
  EXPECT_GT(lit, 400);  // the lit half of the disk, not an empty image
}

TEST(lobe_sphere, rough_dielectric_matches_the_gltf_brdf) { expect_gltf_brdf(0.0, 0.5); }
TEST(lobe_sphere, rough_metal_matches_the_gltf_brdf) { expect_gltf_brdf(1.0, 0.6); }
TEST(lobe_sphere, half_metal_matches_the_gltf_brdf) { expect_gltf_brdf(0.5, 0.3); }

}  // namespace
}  // namespace kiln
