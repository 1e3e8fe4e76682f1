// The view options end to end: --camera by name and index, --look-from, --scene, orthographic
// image size, the default headlight, the degenerate-triangle report and the terminal progress line.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using testing::gltf_builder;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

// A 2x2 quad facing +Z at the origin (plus one degenerate triangle), no lights, two cameras:
// "front" (perspective, 2:1, at z = 4) and "top" (orthographic, xmag 2, ymag 1, at z = 10). Scene 0
// holds the quad and both cameras; scene 1 only the quad moved to x = 100.
std::string write_view_scene(const std::string& folder) {
  gltf_builder b;
  const int quad = b.add_mesh({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, 0}},
                              {0, 1, 2, 0, 2, 3, 4, 4, 4});  // the last triangle repeats a vertex
  const int front = b.add_camera({{"type", "perspective"},
                                  {"name", "front"},
                                  {"perspective", {{"yfov", 0.8}, {"aspectRatio", 2.0}, {"znear", 0.1}}}});
  const int top =
      b.add_camera({{"type", "orthographic"},
                    {"name", "top"},
                    {"orthographic", {{"xmag", 2.0}, {"ymag", 1.0}, {"znear", 0.1}, {"zfar", 100.0}}}});
  b.add_node({{"mesh", quad}});
  b.add_node({{"camera", front}, {"translation", {0, 0, 4}}});
  b.add_node({{"camera", top}, {"translation", {0, 0, 10}}});
  const std::string path = folder + "/view.gltf";
  b.write(path);
  // A second scene: the quad far to the side, seen by no camera.
  nlohmann::json doc;
  std::ifstream(path) >> doc;
  doc["nodes"].push_back({{"mesh", quad}, {"translation", {100, 0, 0}}});
  doc["scenes"].push_back({{"nodes", {doc["nodes"].size() - 1}}});
  std::ofstream(path) << doc.dump();
  return path;
}

struct exr_image {
  int width = 0, height = 0;
  std::vector<float> rgba;  // R G B A Z per pixel
  std::string camera;
  std::array<float, 16> world_to_camera{};
};

exr_image read_exr(const std::string& path) {
  exr_image image;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return image;
  const OIIO::ImageSpec& spec = in->spec();
  image.width = spec.width;
  image.height = spec.height;
  image.camera = spec.get_string_attribute("kiln/camera");
  image.rgba.resize(size_t(spec.width) * spec.height * 5);
  in->read_image(0, 0, 0, 5, OIIO::TypeDesc::FLOAT, image.rgba.data());
  if (const OIIO::ParamValue* m = spec.find_attribute("worldToCamera", OIIO::TypeDesc::TypeMatrix44))
    std::memcpy(image.world_to_camera.data(), m->data(), sizeof(float) * 16);
  return image;
}

float centre_alpha(const exr_image& image) {
  return image.rgba[(size_t(image.height / 2) * image.width + image.width / 2) * 5 + 3];
}

class cli_view : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = scratch_folder("view");
    scene_ = write_view_scene(folder_);
  }
  std::string out(const std::string& name) const { return folder_ + "/" + name + ".exr"; }
  std::string folder_, scene_;
};

TEST_F(cli_view, camera_by_name_and_by_index_select_the_same_camera) {
  for (const char* which : {"top", "1"}) {
    auto result = run_kiln({"render", scene_, "-o", out("camera"), "-q", "--camera", which});
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    exr_image image = read_exr(out("camera"));
    EXPECT_EQ(image.camera, "top") << which;
    // Orthographic xmag 2, ymag 1: with no size given the image takes the view's 2:1 aspect.
    EXPECT_EQ(image.width, 640);
    EXPECT_EQ(image.height, 320);
    // The 2x2 quad spans x in [-1, 1] of the 4-wide view: the centre is covered, the left quarter not.
    EXPECT_EQ(centre_alpha(image), 1.0f);
    EXPECT_EQ(image.rgba[(size_t(160) * 640 + 40) * 5 + 3], 0.0f);
    EXPECT_EQ(image.rgba[(size_t(160) * 640 + 200) * 5 + 3], 1.0f);
  }
  // The default is the first camera, whose aspectRatio 2 sets the height.
  auto result = run_kiln({"render", scene_, "-o", out("first"), "-q", "--width", "64"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  exr_image first = read_exr(out("first"));
  EXPECT_EQ(first.camera, "front");
  EXPECT_EQ(first.height, 32);
  result = run_kiln({"render", scene_, "-o", out("bad"), "-q", "--camera", "5"});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.stderr_text.find("out of range"), std::string::npos) << result.stderr_text;
  EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
  EXPECT_FALSE(fs::exists(out("bad")));
}

TEST_F(cli_view, look_at_camera_overrides_the_file_and_is_recorded_in_the_header) {
  auto result = run_kiln({"render", scene_, "-o", out("look"), "-q", "--width", "48", "--height", "48",
                          "--look-from", "0.5,-0.25,3", "--look-at", "0.5,-0.25,0", "--fov", "30"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  exr_image image = read_exr(out("look"));
  EXPECT_EQ(image.camera, "look-at");
  // OpenEXR's row-vector convention: p_camera = p_world · M. The eye maps to the origin, the
  // target to (0, 0, 3): camera space is left-handed with +Z the viewing direction.
  auto apply = [&](double x, double y, double z, int column) {
    const auto& m = image.world_to_camera;
    return x * m[0 * 4 + column] + y * m[1 * 4 + column] + z * m[2 * 4 + column] + m[3 * 4 + column];
  };
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(apply(0.5, -0.25, 3.0, c), 0.0, 1e-5) << c;
  EXPECT_NEAR(apply(0.5, -0.25, 0.0, 0), 0.0, 1e-5);
  EXPECT_NEAR(apply(0.5, -0.25, 0.0, 2), 3.0, 1e-5);
  // The centre ray hits the quad at distance 3.
  const size_t centre = (size_t(24) * 48 + 24) * 5;
  EXPECT_NEAR(image.rgba[centre + 4], 3.0f, 1e-3f);
}

TEST_F(cli_view, one_end_of_a_look_at_camera_is_refused_before_the_asset_loads) {
  // The asset cannot load (its buffer is missing): the refusal must come from the arguments alone.
  const std::string broken = folder_ + "/broken.gltf";
  std::ofstream(broken)
      << R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "missing.bin", "byteLength": 4}]})";
  for (const char* given : {"--look-from", "--look-at"}) {
    auto result = run_kiln({"render", broken, "-o", out("one_end"), "-q", given, "1,2,3"});
    EXPECT_EQ(result.exit_code, 2) << given;
    EXPECT_EQ(result.stderr_text, "kiln: --look-from/--look-at: give both --look-from and --look-at\n")
        << given;
    EXPECT_FALSE(fs::exists(out("one_end")));
  }
}

TEST_F(cli_view, scene_option_renders_another_scene_and_refuses_a_missing_one) {
  auto result = run_kiln(
      {"render", scene_, "-o", out("scene1"), "-q", "--width", "32", "--height", "32", "--scene", "1"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  // Scene 1 has no camera node: the default camera frames its quad at x = 100.
  exr_image image = read_exr(out("scene1"));
  EXPECT_EQ(image.camera, "default");
  EXPECT_EQ(centre_alpha(image), 1.0f);
  result = run_kiln({"render", scene_, "-o", out("scene5"), "--scene", "5"});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.stderr_text.find("/scenes/5"), std::string::npos) << result.stderr_text;
  EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
}

TEST_F(cli_view, headlight_lights_a_file_without_lights_and_degenerate_triangles_are_reported) {
  auto result = run_kiln(
      {"render", scene_, "-o", out("lit"), "--width", "32", "--height", "16", "--lighting", "headlight"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("headlight"), std::string::npos) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("dropped 1 degenerate triangle "), std::string::npos)
      << result.stderr_text;
  exr_image image = read_exr(out("lit"));
  const size_t centre = (size_t(8) * 32 + 16) * 5;
  // glTF's default material is white, metallic 1, roughness 1: a head-on rough metal reflects
  // a clearly non-zero radiance under the headlight.
  EXPECT_GT(image.rgba[centre + 0], 0.05f);
  EXPECT_EQ(image.rgba[centre + 0], image.rgba[centre + 2]);  // white light, white surface
}

TEST_F(cli_view, progress_line_appears_only_on_a_terminal) {
  // Not a terminal: run_kiln sends stderr to a file.
  auto plain = run_kiln({"render", scene_, "-o", out("plain"), "--width", "32", "--height", "16"});
  ASSERT_EQ(plain.exit_code, 0) << plain.stderr_text;
  EXPECT_EQ(plain.stderr_text.find("ETA"), std::string::npos) << plain.stderr_text;
  // A pseudo-terminal through util-linux script(1).
  const std::string log = folder_ + "/tty.log";
  const std::string command = std::string("script -qec \"'") + KILN_BINARY + "' render '" + scene_ +
                              "' -o '" + out("tty") + "' --width 32 --height 16\" '" + log +
                              "' > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(log);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("100%"), std::string::npos) << text;
  EXPECT_NE(text.find("ETA"), std::string::npos) << text;
}

}  // namespace
}  // namespace kiln
