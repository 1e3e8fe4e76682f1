// Optional asset suite: every glTF sample model in ../shared/assets renders at 256x256 from the
// CLI with finite values and some geometry in view, or, when it requires an extension kiln does
// not support, fails with exit code 2 and a message naming that extension. Skips when absent.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> asset_files() {
  std::vector<std::string> files;
  fs::path root(KILN_SHARED_ASSETS);
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return {"(assets folder absent)"};
  for (auto it = fs::recursive_directory_iterator(root, ec); it != fs::recursive_directory_iterator(); ++it) {
    if (it->path().filename() == "invalid") {
      it.disable_recursion_pending();
      continue;
    }
    std::string ext = it->path().extension().string();
    if (ext == ".gltf" || ext == ".glb") files.push_back(fs::relative(it->path(), root).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// extensionsRequired read straight from the file (JSON, or a GLB's first chunk).
std::vector<std::string> required_extensions(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string json_text = bytes;
  if (file.extension() == ".glb" && bytes.size() >= 20) {
    uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    json_text = bytes.substr(20, length);
  }
  auto doc = nlohmann::json::parse(json_text, nullptr, false);
  std::vector<std::string> required;
  if (doc.is_object() && doc.contains("extensionsRequired"))
    for (const auto& e : doc["extensionsRequired"]) required.push_back(e.get<std::string>());
  return required;
}

class asset_suite : public ::testing::TestWithParam<std::string> {};

TEST_P(asset_suite, renders_or_refuses_clearly) {
  fs::path root(KILN_SHARED_ASSETS);
  if (!fs::is_directory(root)) GTEST_SKIP() << "../shared/assets is absent";
  fs::path file = root / GetParam();
  const std::set<std::string> supported = {"KHR_lights_punctual",
                                           "KHR_materials_emissive_strength",
                                           "KHR_materials_ior",
                                           "KHR_materials_specular",
                                           "KHR_materials_clearcoat",
                                           "KHR_materials_sheen",
                                           "KHR_materials_iridescence",
                                           "KHR_materials_anisotropy",
                                           "KHR_materials_dispersion",
                                           "KHR_materials_diffuse_transmission",
                                           "KHR_materials_transmission",
                                           "KHR_materials_volume",
                                           "KHR_texture_transform",
                                           "KHR_materials_unlit",
                                           "KHR_mesh_quantization",
                                           "EXT_mesh_gpu_instancing",
                                           "KHR_draco_mesh_compression",
                                           "EXT_meshopt_compression",
                                           "EXT_texture_webp"};
  std::string unsupported;
  for (const std::string& e : required_extensions(file))
    if (!supported.count(e)) unsupported = e;

  std::string out = testing::scratch_folder("asset_" + file.stem().string()) + "/out.exr";
  auto result = testing::run_kiln(
      {"render", file.string(), "-o", out, "--width", "256", "--height", "256", "--threads", "2", "-q"});
  if (!unsupported.empty()) {
    EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find(unsupported), std::string::npos) << result.stderr_text;
    EXPECT_EQ(testing::lines(result.stderr_text).size(), 1u) << result.stderr_text;
    return;
  }
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  auto in = OIIO::ImageInput::open(out);
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  size_t covered = 0;
  for (size_t i = 0; i < size_t(spec.width) * spec.height; ++i) {
    const float* p = &pixels[i * spec.nchannels];
    // R G B A and N.X N.Y N.Z are always finite; Z is finite where something was hit, +inf elsewhere.
    ASSERT_EQ(spec.nchannels, 8);
    for (int c : {0, 1, 2, 3, 5, 6, 7}) ASSERT_TRUE(std::isfinite(p[c])) << "pixel " << i << " channel " << c;
    ASSERT_FALSE(std::isnan(p[4])) << "pixel " << i;
    if (p[3] > 0.0f) {
      ++covered;
      ASSERT_TRUE(std::isfinite(p[4]) && p[4] > 0.0f) << "pixel " << i << " depth " << p[4];
    }
  }
  EXPECT_GT(covered, 0u) << "no geometry in view";
}

// RGB of a rendered EXR, or empty when it cannot be read.
std::vector<float> read_rgb(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> rgb(size_t(spec.width) * spec.height * 3);
  if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, rgb.data())) return {};
  return rgb;
}

// KHR_mesh_quantization: the quantized Duck (integer positions, normals and UVs dequantized by
// its node transform and KHR_texture_transform) renders like the float Duck from the same camera,
// up to a few pixels at the silhouette and texture edges where a vertex moved by less than one
// quantization step.
TEST(asset_renders, quantized_duck_renders_like_the_float_duck) {
  fs::path root(KILN_SHARED_ASSETS);
  if (!fs::exists(root / "Duck/glTF-Quantized/Duck.gltf")) GTEST_SKIP() << "../shared/assets is absent";
  const std::string folder = testing::scratch_folder("quantized_duck");
  std::vector<float> images[2];
  const char* files[2] = {"Duck/glTF-Binary/Duck.glb", "Duck/glTF-Quantized/Duck.gltf"};
  for (int i = 0; i < 2; ++i) {
    const std::string out = folder + "/duck" + std::to_string(i) + ".exr";
    auto result = testing::run_kiln({"render", (root / files[i]).string(), "-o", out, "--width", "128",
                                     "--height", "128", "--threads", "2", "-q", "--lighting", "headlight"});
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    images[i] = read_rgb(out);
    ASSERT_EQ(images[i].size(), size_t(128) * 128 * 3);
  }
  size_t differing = 0, lit = 0;
  double total = 0.0;
  for (size_t p = 0; p < images[0].size() / 3; ++p) {
    float worst = 0.0f;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(images[0][3 * p + c] - images[1][3 * p + c]));
    differing += worst > 0.02f;
    lit += images[0][3 * p] + images[0][3 * p + 1] + images[0][3 * p + 2] > 0.0f;
    total += worst;
  }
  EXPECT_GT(lit, 1000u);  // the duck fills a good part of the frame
  // Mip-mapped texturing picks its level from each triangle's UV and position derivatives, which
  // quantization perturbs too; high-contrast texels (the eyes) then differ: allow 2% of the duck.
  EXPECT_LE(differing, lit / 50);
  EXPECT_LT(total / double(images[0].size() / 3), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(shared_assets, asset_suite, ::testing::ValuesIn(asset_files()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name;
                           for (char c : param_info.param)
                             name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

}  // namespace
}  // namespace kiln
