// OpenImageIO lives in the image codecs module, which kiln opens only when a render meets an
// image that kiln does not decode itself (it decodes 8-bit PNG and JPEG, core glTF's formats):
// with KILN_IMAGE_CODECS naming a file that does not exist, `kiln --version`, a render without
// textures, one with PNG textures, previews and contact sheets succeed (the module is never looked
// for), while a WebP texture or an environment map fail with one line naming the path. Without the
// variable kiln looks beside itself, then in ../lib/kiln/ (an install), then in the build tree.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "io/image_codecs/direct_decode.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using testing::command_result;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

const std::string scenes = std::string(KILN_SOURCE_DIR) + "/scenes/";
const std::string untextured = scenes + "quadric_showcase.gltf";
const std::string png_textured = scenes + "cornell_box.gltf";  // samples checker.png
const std::string missing_module = "/nonexistent/path.so";

// A 4x4 lossy WebP of pure green (oiiotool --pattern constant:color=0,1,0 4x4 3).
const std::vector<uint8_t> green_webp = {
    82,  73,  70,  70,  68,  0,   0,   0,   87,  69,  66,  80,  86, 80,  56,  32,  56,  0,   0,
    0,   80,  2,   0,   157, 1,   42,  4,   0,   4,   0,   0,   0,  0,   37,  160, 2,   116, 186,
    1,   248, 1,   250, 1,   252, 0,   7,   144, 0,   254, 251, 15, 139, 255, 238, 148, 37,  201,
    154, 110, 127, 251, 165, 15,  255, 233, 234, 147, 103, 201, 49, 151, 255, 167, 113, 0,   0};

// The Cornell box in `folder` with its texture read from a WebP (EXT_texture_webp), which only the
// module decodes. Returns the glTF's path.
std::string webp_textured_scene(const fs::path& folder) {
  fs::create_directories(folder);
  std::ifstream in(png_textured);
  nlohmann::json doc = nlohmann::json::parse(in);
  const std::string buffer = doc["buffers"][0]["uri"].get<std::string>();
  fs::copy_file(fs::path(scenes) / buffer, folder / buffer, fs::copy_options::overwrite_existing);
  doc["images"] = nlohmann::json::array({nlohmann::json{{"uri", "green.webp"}}});
  doc["extensionsUsed"].push_back("EXT_texture_webp");
  doc["textures"][0]["extensions"]["EXT_texture_webp"] = {{"source", 0}};
  doc["textures"][0].erase("source");
  std::ofstream(folder / "green.webp", std::ios::binary)
      .write(reinterpret_cast<const char*>(green_webp.data()), std::streamsize(green_webp.size()));
  const fs::path path = folder / "webp_box.gltf";
  std::ofstream(path) << doc.dump();
  return path.string();
}

// Sets KILN_IMAGE_CODECS for the kiln processes a test starts, and clears it afterwards.
struct codecs_variable {
  explicit codecs_variable(const std::string& value) { ::setenv("KILN_IMAGE_CODECS", value.c_str(), 1); }
  ~codecs_variable() { ::unsetenv("KILN_IMAGE_CODECS"); }
};

std::vector<std::string> small_render(const std::string& scene, const std::string& out) {
  return {"render", scene, "-o", out, "--width", "16", "--height", "12"};
}

// The run failed (not with a crash) on exactly one line that names the module's path.
void expect_module_error(const command_result& result, const std::string& path, const std::string& needs) {
  EXPECT_EQ(result.exit_code, 1) << result.stderr_text;
  ASSERT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
  EXPECT_EQ(result.stderr_text.rfind("kiln: " + needs + " the image codecs module: " + path, 0), 0u)
      << result.stderr_text;
}

TEST(image_codecs_cli, version_never_looks_for_the_module) {
  const codecs_variable variable(missing_module);
  const command_result result = run_kiln({"--version"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(result.stderr_text, "");
}

// Neither a scene without images nor one with PNG textures (kiln decodes those itself) opens it.
TEST(image_codecs_cli, renders_without_images_or_with_png_textures_never_look_for_the_module) {
  const codecs_variable variable(missing_module);
  for (const std::string& scene : {untextured, png_textured}) {
    const std::string out = scratch_folder("codecs_" + fs::path(scene).stem().string()) + "/out.exr";
    const command_result result = run_kiln(small_render(scene, out));
    EXPECT_EQ(result.exit_code, 0) << scene << ": " << result.stderr_text;
    EXPECT_TRUE(fs::is_regular_file(out)) << scene;
  }
}

TEST(image_codecs_cli, textured_scene_without_the_module_fails_naming_its_path) {
  const codecs_variable variable(missing_module);
  const std::string dir = scratch_folder("codecs_textured");
  const std::string out = dir + "/out.exr";
  const command_result result = run_kiln(small_render(webp_textured_scene(dir), out));
  expect_module_error(result, missing_module, "textures need");
  EXPECT_NE(result.stderr_text.find("No such file"), std::string::npos) << result.stderr_text;
  EXPECT_FALSE(fs::exists(out));
}

TEST(image_codecs_cli, an_environment_map_needs_the_module) {
  const codecs_variable variable(missing_module);
  const std::string dir = scratch_folder("codecs_environment");
  std::vector<std::string> args = small_render(untextured, dir + "/env.exr");
  args.insert(args.end(), {"--environment", scenes + "glass_showcase_sky.hdr"});
  expect_module_error(run_kiln(args), missing_module, "an environment map needs");
  EXPECT_FALSE(fs::exists(dir + "/env.exr"));
}

// The sRGB code of a linear value, written out independently of kiln's code.
int srgb_code(double v) {
  return int(std::lround(255.0 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055)));
}

std::vector<uint8_t> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// kiln encodes previews and contact sheets itself (libpng, libjpeg): with no module to be found, a
// render of nothing but a constant background seen by the camera writes a PNG that libpng decodes
// to that colour's sRGB codes at every pixel, a JPEG within a code of them, and a batch its sheet.
TEST(image_codecs_cli, previews_and_contact_sheets_never_look_for_the_module) {
  const codecs_variable variable(missing_module);
  const std::string dir = scratch_folder("codecs_preview");
  testing::gltf_builder b;
  b.add_node({{"mesh", b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2})}});
  const std::string scene = dir + "/triangle.gltf";
  b.write(scene);
  // Looking away from the triangle: every pixel is the background. 0.25, 0.5 and 0.75 are exact
  // in the EXR's half.
  const std::vector<std::string> view = {
      "--background", "0.25,0.5,0.75", "--show-background", "--look-from", "0,0,5", "--look-at", "0,0,10"};
  const int expected[3] = {srgb_code(0.25), srgb_code(0.5), srgb_code(0.75)};
  EXPECT_EQ(expected[0], 137);
  for (const std::string extension : {"png", "jpg"}) {
    const std::string preview = dir + "/background." + extension;
    std::vector<std::string> args = small_render(scene, dir + "/background.exr");
    args.insert(args.end(), view.begin(), view.end());
    args.insert(args.end(), {"--preview", preview});
    const command_result result = run_kiln(args);
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    const std::vector<uint8_t> bytes = file_bytes(preview);
    const std::optional<image> decoded = decode_directly(bytes.data(), bytes.size(), 16 * 12);
    ASSERT_TRUE(decoded) << preview;
    ASSERT_EQ(decoded->width, 16);
    ASSERT_EQ(decoded->height, 12);
    int worst = 0;
    for (size_t i = 0; i < 16 * 12; ++i) {
      for (size_t c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(int(decoded->texels8[i * 4 + c]) - expected[c]));
      EXPECT_EQ(decoded->texels8[i * 4 + 3], 255) << preview << " pixel " << i;
    }
    // PNG is lossless; JPEG's YCbCr round trip moves a flat colour by at most a code.
    EXPECT_EQ(worst, extension == "png" ? 0 : 1) << preview;
  }

  const std::string sheet = dir + "/sheet.png";
  const command_result batch = run_kiln({"batch", scene, "--out-dir", dir + "/batch", "--width", "16",
                                         "--height", "12", "-q", "--contact-sheet", sheet});
  EXPECT_EQ(batch.exit_code, 0) << batch.stderr_text;
  const std::vector<uint8_t> sheet_bytes = file_bytes(sheet);
  EXPECT_TRUE(decode_directly(sheet_bytes.data(), sheet_bytes.size(), 1 << 20)) << sheet;
}

TEST(image_codecs_cli, a_file_that_is_no_module_is_reported_on_one_line) {
  const std::string fake = scratch_folder("codecs_fake") + "/kiln_image_codecs.so";
  std::ofstream(fake) << "not a shared object\n";
  const codecs_variable variable(fake);
  const fs::path dir = fs::path(fake).parent_path();
  expect_module_error(run_kiln(small_render(webp_textured_scene(dir), dir / "out.exr")), fake,
                      "textures need");
}

TEST(image_codecs_cli, variable_naming_the_module_renders_textures) {
  const codecs_variable variable(KILN_IMAGE_CODECS_MODULE);
  const std::string dir = scratch_folder("codecs_named");
  const std::string out = dir + "/out.exr";
  const std::string preview = fs::path(out).replace_extension(".png").string();
  std::vector<std::string> args = small_render(webp_textured_scene(dir), out);
  args.insert(args.end(), {"--preview", preview});
  const command_result result = run_kiln(args);
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_TRUE(fs::is_regular_file(out));
  EXPECT_TRUE(fs::is_regular_file(preview));
}

// A kiln copied into an install layout (prefix/bin/kiln) looks beside itself first, then in
// prefix/lib/kiln/. A file there that does not open is reported, not passed over for the build
// tree's module.
TEST(image_codecs_cli, installed_kiln_looks_beside_itself_then_in_lib_kiln) {
  const fs::path prefix = scratch_folder("codecs_install");
  fs::create_directories(prefix / "bin");
  fs::create_directories(prefix / "lib/kiln");
  const fs::path kiln = prefix / "bin/kiln";
  fs::copy_file(KILN_BINARY, kiln);
  const auto render = [&](const std::string& name) {
    const std::string command = "'" + kiln.string() + "' render '" + webp_textured_scene(prefix / "scene") +
                                "' -o '" + (prefix / name).string() + "' --width 16 --height 12 2> '" +
                                (prefix / "stderr.txt").string() + "'";
    command_result result;
    const int status = std::system(command.c_str());
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(prefix / "stderr.txt");
    result.stderr_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return result;
  };

  const fs::path in_lib = prefix / "lib/kiln/kiln_image_codecs.so";
  std::ofstream(in_lib) << "broken install\n";
  expect_module_error(render("a.exr"), in_lib.string(), "textures need");

  const fs::path beside = prefix / "bin/kiln_image_codecs.so";
  std::ofstream(beside) << "broken copy\n";
  expect_module_error(render("b.exr"), beside.string(), "textures need");

  fs::remove(beside);
  fs::copy_file(KILN_IMAGE_CODECS_MODULE, in_lib, fs::copy_options::overwrite_existing);
  const command_result installed = render("c.exr");
  EXPECT_EQ(installed.exit_code, 0) << installed.stderr_text;
  EXPECT_TRUE(fs::is_regular_file(prefix / "c.exr"));
}

}  // namespace
}  // namespace kiln
