// The speed options end to end: `--bvh-quality`, `--bvh-compact` and `--packets` are recorded in the
// EXR header and in kiln bench's JSON, refuse bad values with one line, and leave the pixels byte
// for byte as the default render's on a small mesh room built here: all meshes, so packets are
// really traced (the demo scene holds quadrics, which Embree answers one ray at a time), and no
// coincident surfaces, the one case where packets may pick the other surface of a tie (see
// docs/performance.md, "Summary").
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

// An axis-aligned box as 8 corners and 12 triangles, counter-clockwise seen from outside.
void add_box(testing::gltf_builder& b, std::array<float, 3> lo, std::array<float, 3> hi, int material) {
  std::vector<std::array<float, 3>> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back({i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]});
  std::vector<uint32_t> indices;
  for (const auto& q : {std::array<uint32_t, 4>{0, 2, 3, 1},
                        {4, 5, 7, 6},
                        {0, 1, 5, 4},
                        {2, 6, 7, 3},
                        {0, 4, 6, 2},
                        {1, 3, 7, 5}})
    indices.insert(indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  b.add_node({{"mesh", b.add_mesh(corners, indices, material)}});
}

// A room of meshes: floor, back and side walls (quads meeting only at their edges), a mirror box
// and a diffuse box standing on the floor, a point light and a camera.
std::string write_mesh_room() {
  testing::gltf_builder b;
  auto matte = [&](float r, float g, float bl) {
    return b.add_material(
        {{"pbrMetallicRoughness",
          {{"baseColorFactor", {r, g, bl, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}});
  };
  const int white = matte(0.7f, 0.7f, 0.7f), red = matte(0.6f, 0.1f, 0.1f), green = matte(0.1f, 0.5f, 0.1f);
  const int mirror = b.add_material(
      {{"pbrMetallicRoughness",
        {{"baseColorFactor", {0.9, 0.9, 0.9, 1.0}}, {"metallicFactor", 1.0}, {"roughnessFactor", 0.0}}}});
  auto quad = [&](std::array<std::array<float, 3>, 4> corners, int material) {
    b.add_node({{"mesh", b.add_mesh({corners.begin(), corners.end()}, {0, 1, 2, 0, 2, 3}, material)}});
  };
  quad({{{-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}}}, white);    // floor, facing +y
  quad({{{-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}}}, white);  // back wall, facing +z
  quad({{{-1, 0, 1}, {-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1}}}, red);    // left wall, facing +x
  quad({{{1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1}}}, green);      // right wall, facing -x
  add_box(b, {-0.7f, 0.0f, -0.6f}, {-0.1f, 1.2f, -0.1f}, mirror);
  add_box(b, {0.2f, 0.0f, 0.0f}, {0.7f, 0.5f, 0.5f}, white);
  b.add_node(
      {{"translation", {0.2, 1.8, 0.6}},
       {"extensions",
        {{"KHR_lights_punctual", {{"light", b.add_light({{"type", "point"}, {"intensity", 6.0}})}}}}}});
  b.add_node({{"translation", {0.0, 1.0, 3.5}},
              {"camera",
               b.add_camera({{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.05}}}})}});
  const std::string path = testing::scratch_folder("perf_mesh_room") + "/mesh_room.gltf";
  b.write(path);
  return path;
}

const std::string mesh_scene = write_mesh_room();

std::string render(const std::string& dir, const std::string& name, std::vector<std::string> extra) {
  std::vector<std::string> args = {
      "render", mesh_scene, "-o", dir + "/" + name, "--width",           "40", "--height", "30",
      "-q",     "--spp",    "2",  "--aovs",         "beauty,Z,N,P,uv,id"};
  args.insert(args.end(), extra.begin(), extra.end());
  auto result = run_kiln(args);
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  return dir + "/" + name;
}

struct stored_image {
  OIIO::ImageSpec spec;
  std::vector<unsigned char> bytes;  // as stored (half and float)
};

stored_image read(const std::string& path) {
  stored_image out;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return out;
  out.spec = in->spec();
  out.bytes.resize(out.spec.image_bytes(true));
  in->read_image(0, 0, 0, out.spec.nchannels, OIIO::TypeUnknown, out.bytes.data());
  return out;
}

std::vector<float> read_floats(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> values(size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, values.data());
  return values;
}

TEST(perf_options_cli, defaults_are_recorded_in_the_header) {
  const stored_image a = read(render(scratch_folder("perf_default"), "a.exr", {}));
  EXPECT_EQ(a.spec.get_string_attribute("kiln/bvh_quality"), "medium");
  EXPECT_EQ(a.spec.get_string_attribute("kiln/bvh_compact"), "off");
  EXPECT_EQ(a.spec.get_string_attribute("kiln/packets"), "on");
}

TEST(perf_options_cli, every_build_setting_and_packets_leave_the_pixels_unchanged) {
  const std::string dir = scratch_folder("perf_settings");
  const stored_image reference = read(render(dir, "reference.exr", {}));
  ASSERT_FALSE(reference.bytes.empty());
  int n = 0;
  for (const char* quality : {"low", "medium", "high"})
    for (bool compact : {false, true})
      for (const char* packets : {"off", "on"}) {
        std::vector<std::string> args = {"--bvh-quality", quality, "--packets", packets};
        if (compact) args.push_back("--bvh-compact");
        const stored_image img = read(render(dir, std::to_string(n++) + ".exr", args));
        SCOPED_TRACE(std::string(quality) + (compact ? " compact " : " ") + packets);
        EXPECT_EQ(img.spec.get_string_attribute("kiln/bvh_quality"), quality);
        EXPECT_EQ(img.spec.get_string_attribute("kiln/bvh_compact"), compact ? "on" : "off");
        EXPECT_EQ(img.spec.get_string_attribute("kiln/packets"), packets);
        ASSERT_EQ(img.bytes.size(), reference.bytes.size());
        if (!compact) {  // the build quality and packets change only the tree and the traversal
          EXPECT_EQ(std::memcmp(img.bytes.data(), reference.bytes.data(), img.bytes.size()), 0);
          continue;
        }
        // The compact layout computes triangle edges at query time: on CPUs whose Embree kernels
        // differ there (AVX2), hits move by float rounding; every channel stays within it.
        const std::vector<float> a = read_floats(dir + "/" + std::to_string(n - 1) + ".exr");
        const std::vector<float> b = read_floats(dir + "/reference.exr");
        ASSERT_EQ(a.size(), b.size());
        float worst = 0.0f;
        for (size_t i = 0; i < a.size(); ++i)
          worst = std::max(worst, std::abs(a[i] - b[i]) / std::max(1.0f, std::abs(b[i])));
        EXPECT_LE(worst, 2e-3f);  // a half's ulp near 1 is 1e-3
      }
}

TEST(perf_options_cli, with_packets_the_image_is_independent_of_threads_and_tile_size) {
  const std::string dir = scratch_folder("perf_packets_tiles");
  const stored_image reference = read(render(dir, "reference.exr", {"--threads", "1"}));
  int n = 0;
  for (const char* threads : {"1", "2", "3"})
    for (const char* tile : {"1", "5", "32", "64"}) {
      SCOPED_TRACE(std::string(threads) + " threads, tile " + tile);
      const stored_image img = read(render(dir, std::to_string(n++) + ".exr",
                                           {"--packets", "on", "--threads", threads, "--tile-size", tile}));
      ASSERT_EQ(img.bytes.size(), reference.bytes.size());
      EXPECT_EQ(std::memcmp(img.bytes.data(), reference.bytes.data(), img.bytes.size()), 0);
    }
}

TEST(perf_options_cli, bad_values_exit_2_with_one_line) {
  for (std::vector<std::string> bad :
       {std::vector<std::string>{"--bvh-quality", "best"}, std::vector<std::string>{"--packets", "yes"}}) {
    std::vector<std::string> args = {"render", mesh_scene, "-o", scratch_folder("perf_bad") + "/x.exr"};
    args.insert(args.end(), bad.begin(), bad.end());
    auto result = run_kiln(args);
    EXPECT_EQ(result.exit_code, 2) << bad[0];
    EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find(bad[0]), std::string::npos) << result.stderr_text;
  }
}

TEST(perf_options_cli, bench_json_records_the_settings_and_embree_memory) {
  const std::string json = scratch_folder("perf_bench") + "/bench.json";
  auto result = run_kiln({"bench", mesh_scene, "--width", "32", "--height", "24", "--repeat", "1", "-q",
                          "--bvh-quality", "high", "--bvh-compact", "--packets", "on", "--json", json});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  std::ifstream in(json);
  const nlohmann::json r = nlohmann::json::parse(in);
  EXPECT_EQ(r["bvh_quality"], "high");
  EXPECT_EQ(r["bvh_compact"], true);
  EXPECT_EQ(r["packets"], true);
  EXPECT_GT(r["embree_bytes"]["after_build"].get<size_t>(), 0u);
  EXPECT_GE(r["embree_bytes"]["peak"].get<size_t>(), r["embree_bytes"]["after_build"].get<size_t>());
  // The camera rays were also replayed as coherent streams.
  bool camera_streamed = false;
  for (const auto& k : r["kinds"])
    if (k["kind"] == "camera" && k["query"] == "intersect")
      camera_streamed = k.contains("bare_stream_mrays_per_s");
  EXPECT_TRUE(camera_streamed);
}

TEST(perf_options_cli, bench_reports_no_streams_for_quadric_scenes) {
  // Quadric user geometry answers single rays only: a stream would miss every quadric and report
  // a speed for rays that never met one. The single-ray rows must still find the quadrics.
  const std::string json = scratch_folder("perf_bench_quadrics") + "/bench.json";
  auto result = run_kiln({"bench", std::string(KILN_SOURCE_DIR) + "/scenes/quadric_showcase.gltf", "--width",
                          "32", "--height", "24", "--repeat", "1", "-q", "--json", json});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  std::ifstream in(json);
  const nlohmann::json r = nlohmann::json::parse(in);
  size_t camera_hits = 0;
  for (const auto& k : r["kinds"]) {
    EXPECT_FALSE(k.contains("bare_stream_mrays_per_s")) << k.dump();
    if (k["kind"] == "camera" && k["query"] == "intersect") camera_hits = k["hits"].get<size_t>();
  }
  EXPECT_GT(camera_hits, 32u * 24u / 4u);  // the showcase fills most of the frame with quadrics
}

}  // namespace
}  // namespace kiln
