// KHR_materials_dispersion through a glass ball: parallel camera rays cross a unit sphere of
// dispersive glass (ior 1.5, dispersion 1: Abbe number 20) and land on a white unlit half-plane
// far behind it. Each colour channel leaves the ball bent by its own ior, so near the half-plane's edge
// a ray's red can land on it while its blue misses, or the reverse. Snell's law per channel, in
// double, says which channel of every ray must be lit; without dispersion the three always agree.
#include <gtest/gtest.h>

#include <optional>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "shade/material_lobes.h"
#include "shade/whitted.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

constexpr double plane_z = -12.0;  // the half-plane x > edge, facing the camera
constexpr double edge = 3.0;

std::optional<dvec3> refract(const dvec3& d, const dvec3& n, double eta) {
  const double cos_i = -glm::dot(d, n);
  const double k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
  if (k < 0.0) return std::nullopt;
  return eta * d + (eta * cos_i - std::sqrt(k)) * n;
}

// Where the ray down −z at (x, 0) lands on the plane after crossing the unit ball of ior n, if it
// gets through (no total internal reflection).
std::optional<double> landing_x(double x, double n) {
  const dvec3 entry(x, 0.0, std::sqrt(1.0 - x * x));
  const std::optional<dvec3> inside = refract({0.0, 0.0, -1.0}, entry, 1.0 / n);
  if (!inside) return std::nullopt;
  const dvec3 exit = entry - 2.0 * glm::dot(entry, *inside) * *inside;
  const std::optional<dvec3> out = refract(*inside, -exit, n);
  if (!out || out->z >= 0.0) return std::nullopt;
  return exit.x + out->x * (plane_z - exit.z) / out->z;
}

std::string write_ball(double dispersion, const std::string& name) {
  testing::gltf_builder b;
  const int white = b.add_material({{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}}},
                                    {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}});
  const float z = float(plane_z), e = float(edge);
  const int plane =
      b.add_mesh({{e, -80, z}, {80, -80, z}, {80, 80, z}, {e, 80, z}}, {0, 1, 2, 0, 2, 3}, white);
  nlohmann::json glass = {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 0.0}}},
                          {"extensions",
                           {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                            {"KHR_materials_volume", {{"thicknessFactor", 2.0}}}}}};
  if (dispersion > 0.0) glass["extensions"]["KHR_materials_dispersion"] = {{"dispersion", dispersion}};
  const int ball = b.add_material(glass);
  b.doc["extensionsUsed"] = {"KHR_materials_unlit", "KHR_materials_transmission", "KHR_materials_volume",
                             "KHR_materials_dispersion", "KILN_quadric"};
  b.doc["extensions"]["KILN_quadric"]["primitives"] = {{{"kind", "sphere"}, {"radius", 1.0}}};
  b.add_node({{"mesh", plane}});
  b.add_node({{"extensions", {{"KILN_quadric", {{"primitive", 0}, {"material", ball}}}}}});
  return b.write(testing::scratch_folder("dispersion_" + name) + "/ball.gltf");
}

// Counts the rays whose channels disagree (one lit, another dark) and checks every channel of every
// ray against Snell's law: lit (most of the white arrives) or dark (at most stray reflections).
int expect_channels_follow_snell(double dispersion, const std::string& name) {
  const scene world = load_gltf(write_ball(dispersion, name));
  const embree_accelerator accel(world);
  const shading_options options;
  const shading_context ctx{world, accel, options};
  const vec3 iors = dispersed_ior(1.5f, float(dispersion));
  int split = 0, checked = 0;
  for (int i = 0; i < 800; ++i) {
    const double x = -0.9 + 1.8 * (i + 0.5) / 800.0;
    ray r;
    r.origin = vec3(float(x), 0.0f, 10.0f);
    r.direction = vec3(0.0f, 0.0f, -1.0f);
    r.kind = ray_kind::camera;
    ray_counts counts;
    const vec3 radiance = trace_radiance(ctx, r, path_state{}, counts);
    bool lit[3];
    bool clear = true;
    for (int c = 0; c < 3; ++c) {
      const std::optional<double> lands = landing_x(x, double(iors[c]));
      if (lands && std::abs(*lands - edge) < 0.005) clear = false;  // too near the edge to call
      lit[c] = lands && *lands > edge;
    }
    if (!clear) continue;
    ++checked;
    for (int c = 0; c < 3; ++c) {
      if (lit[c])
        EXPECT_GT(radiance[c], 0.5f) << name << " x " << x << " channel " << c;
      else
        EXPECT_LT(radiance[c], 0.2f) << name << " x " << x << " channel " << c;
    }
    if (lit[0] != lit[2]) ++split;
  }
  EXPECT_GT(checked, 750) << name;
  return split;
}

TEST(dispersion, each_channel_refracts_by_its_own_ior) {
  // Abbe number 20: red 1.4863, blue 1.5244 (the extension's formula about 587.6 nm).
  const vec3 iors = dispersed_ior(1.5f, 1.0f);
  EXPECT_NEAR(iors.g, 1.5f, 2e-4f);
  EXPECT_NEAR(iors.b - iors.r, 0.5f / 20.0f * (523655.0f / (486.1f * 486.1f) - 523655.0f / (656.3f * 656.3f)),
              1e-5f);
  EXPECT_GT(expect_channels_follow_snell(1.0, "dispersive"), 3);
}

TEST(dispersion, without_it_the_channels_stay_together) {
  EXPECT_EQ(expect_channels_follow_snell(0.0, "plain"), 0);
}

}  // namespace
}  // namespace kiln
