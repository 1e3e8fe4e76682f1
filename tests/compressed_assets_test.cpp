// Compressed glTF renders like its original: each KHR_draco_mesh_compression variant in
// ../shared/assets is traced with the same camera rays as its uncompressed original (Embree, a
// 160x160 pinhole view framing the original), posed at t = 0 and, for animated assets, at a
// later time. Coverage (hit or miss per ray) and depth must agree within the tolerances below,
// which Draco's position quantisation explains. Skips when the assets folder is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

constexpr int side = 160;
// Draco stores positions as integers over the mesh's bounding box (Khronos' variants use 14 bits,
// a step of diagonal/16384 = 6e-5 of the diagonal): a ray's depth moves by about that step, more
// where it grazes a surface, and a ray near a silhouette may change from hit to miss.
constexpr double max_coverage_change = 0.005;     // of all rays
constexpr double max_median_depth_change = 2e-4;  // of the scene's diagonal
constexpr double max_p99_depth_change = 1e-2;     // of the scene's diagonal (grazing rays)

struct view_comparison {
  size_t rays = 0, hits_original = 0, coverage_changes = 0;
  double median_depth = 0, p99_depth = 0;  // |Δt| over the diagonal, rays hit in both
};

size_t triangles(const scene& s) {
  size_t n = 0;
  for (const instance& inst : s.instances)
    if (inst.kind == shape_kind::mesh) n += s.meshes[inst.shape].triangle_count();
  return n;
}

// The view: from the bounds' centre along (1, 0.6, 1.4) at 2.2 radii, looking at the centre.
std::vector<ray> camera_rays(const bounds3& b) {
  const dvec3 centre = b.center();
  const double radius = 0.5 * glm::length(b.diagonal());
  const dvec3 eye = centre + 2.2 * radius * glm::normalize(dvec3(1.0, 0.6, 1.4));
  const dvec3 forward = glm::normalize(centre - eye);
  const dvec3 right = glm::normalize(glm::cross(forward, dvec3(0, 1, 0)));
  const dvec3 up = glm::cross(right, forward);
  std::vector<ray> rays;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const double sx = (x + 0.5) / side * 2.0 - 1.0, sy = 1.0 - (y + 0.5) / side * 2.0;
      ray r;
      r.origin = vec3(eye);
      r.direction = vec3(glm::normalize(forward + 0.5 * (sx * right + sy * up)));
      rays.push_back(r);
    }
  return rays;
}

view_comparison compare_views(const scene& original, const scene& compressed) {
  const bounds3 b = world_bounds(original);
  const double diagonal = glm::length(b.diagonal());
  embree_accelerator a(original), c(compressed);
  view_comparison out;
  std::vector<double> depth;
  for (const ray& r : camera_rays(b)) {
    const std::optional<hit> ha = a.intersect(r), hc = c.intersect(r);
    ++out.rays;
    out.hits_original += ha.has_value();
    if (ha.has_value() != hc.has_value()) ++out.coverage_changes;
    if (ha && hc)
      depth.push_back(std::abs(double(ha->t) - double(hc->t)) * glm::length(dvec3(r.direction)) / diagonal);
  }
  if (!depth.empty()) {
    std::sort(depth.begin(), depth.end());
    out.median_depth = depth[depth.size() / 2];
    out.p99_depth = depth[std::min(depth.size() - 1, depth.size() * 99 / 100)];
  }
  return out;
}

struct asset_pair {
  const char* original;
  const char* draco;
  double posed_time;  // a second pose for animated assets (< 0: still)
};

class draco_variant : public ::testing::TestWithParam<asset_pair> {};

TEST_P(draco_variant, renders_like_its_original) {
  const fs::path root(KILN_SHARED_ASSETS);
  if (!fs::is_directory(root)) GTEST_SKIP() << "../shared/assets is absent";
  const asset_pair& pair = GetParam();
  std::vector<double> times = {0.0};
  if (pair.posed_time >= 0) times.push_back(pair.posed_time);
  for (const double time : times) {
    SCOPED_TRACE("time " + std::to_string(time));
    gltf_load_options options;
    options.time = time;
    const scene original = load_gltf((root / pair.original).string(), options);
    const scene compressed = load_gltf((root / pair.draco).string(), options);
    // The same triangles, but for those the quantisation collapses to zero area (BrainStem has
    // a dozen smaller than a quantisation step), which the loader drops as degenerate.
    ASSERT_LE(triangles(compressed), triangles(original));
    EXPECT_EQ(triangles(original) - triangles(compressed),
              compressed.stats.degenerate_triangles_dropped - original.stats.degenerate_triangles_dropped);
    EXPECT_LE(triangles(original) - triangles(compressed), triangles(original) / 1000);
    ASSERT_EQ(compressed.instances.size(), original.instances.size());
    const view_comparison v = compare_views(original, compressed);
    std::printf(
        "%s at t=%g: %zu of %zu rays hit, %zu coverage changes, |dt|/diagonal median %.2g, p99 %.2g\n",
        pair.draco, time, v.hits_original, v.rays, v.coverage_changes, v.median_depth, v.p99_depth);
    EXPECT_GT(v.hits_original, v.rays / 20) << "the view misses the asset";
    EXPECT_LE(double(v.coverage_changes), max_coverage_change * double(v.rays));
    EXPECT_LE(v.median_depth, max_median_depth_change);
    EXPECT_LE(v.p99_depth, max_p99_depth_change);
  }
}

INSTANTIATE_TEST_SUITE_P(
    assets, draco_variant,
    ::testing::Values(
        asset_pair{"Box/glTF-Binary/Box.glb", "Box/glTF-Draco/Box.gltf", -1},
        asset_pair{"RiggedSimple/glTF-Binary/RiggedSimple.glb", "RiggedSimple/glTF-Draco/RiggedSimple.gltf",
                   1.0},
        asset_pair{"CesiumMan/glTF-Binary/CesiumMan.glb", "CesiumMan/glTF-Draco/CesiumMan.gltf", 1.0},
        asset_pair{"MorphPrimitivesTest/glTF-Binary/MorphPrimitivesTest.glb",
                   "MorphPrimitivesTest/glTF-Draco/MorphPrimitivesTest.gltf", -1},
        asset_pair{"BrainStem/glTF-Binary/BrainStem.glb", "BrainStem/glTF-Draco/BrainStem.gltf", 2.0}),
    [](const ::testing::TestParamInfo<asset_pair>& info) {
      return fs::path(info.param.draco).stem().string();
    });

// A corrupt Draco stream is bad input: one line naming the file and the extension's pointer, exit 2.
TEST(draco_cli, corrupt_stream_exits_2_with_one_line) {
  testing::gltf_builder b;
  const std::vector<uint8_t> garbage(96, 0x5a);
  const int view = b.add_view(garbage.data(), garbage.size());
  const int pos = b.add_accessor(-1, 5126, 3, "VEC3");
  b.doc["accessors"][size_t(pos)]["min"] = {0.0, 0.0, 0.0};
  b.doc["accessors"][size_t(pos)]["max"] = {1.0, 1.0, 0.0};
  const nlohmann::json ext = {{"bufferView", view}, {"attributes", {{"POSITION", 0}}}};
  const int mesh = b.add_mesh(
      {{"attributes", {{"POSITION", pos}}}, {"extensions", {{"KHR_draco_mesh_compression", ext}}}});
  b.set_scene({b.add_node({{"mesh", mesh}})});
  b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  const std::string folder = testing::scratch_folder("draco_cli");
  const std::string path = b.write(folder + "/corrupt.gltf");
  const testing::command_result r = testing::run_kiln({"render", path, "-o", folder + "/out.exr"});
  EXPECT_EQ(r.exit_code, 2);
  const std::vector<std::string> lines = testing::lines(r.stderr_text);
  ASSERT_EQ(lines.size(), 1u) << r.stderr_text;
  EXPECT_NE(
      lines[0].find(path +
                    ": /meshes/0/primitives/0/extensions/KHR_draco_mesh_compression: corrupt Draco stream"),
      std::string::npos)
      << lines[0];
  EXPECT_FALSE(fs::exists(folder + "/out.exr"));
}

}  // namespace
}  // namespace kiln
