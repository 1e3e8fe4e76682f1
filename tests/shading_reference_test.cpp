// The wave shading core held to the reference (--shading reference: each sample shaded from its
// camera ray to its last bounce, one at a time) on every shipped scene and every sample model in
// ../shared/assets (one file a model; skipped when the folder is absent), as `kiln compare` holds
// Embree to the grid. The bound, per image: the mean absolute difference of R, G, B, A at most 1e-4
// of the reference's range, and no pixel off by more than 1% of that range away from edges (a pixel
// whose id.object differs from a neighbour's, or whose alpha is partial). The wave runs the same
// lobe functions, so today the two agree bit for bit; the bound is what later wave stages (float
// evaluation over groups, forward accumulation) must keep.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

// The shipped scenes, and each sample model's first glTF (or GLB) file.
std::vector<std::string> scene_files() {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::path(KILN_SOURCE_DIR) / "scenes", ec))
    if (e.path().extension() == ".gltf") files.push_back(e.path().string());
  const fs::path assets(KILN_SHARED_ASSETS);
  for (const auto& model : fs::directory_iterator(assets, ec)) {
    if (!model.is_directory() || model.path().filename() == "invalid") continue;
    for (const char* variant : {"glTF", "glTF-Binary"}) {
      std::vector<fs::path> found;
      for (const auto& f : fs::directory_iterator(model.path() / variant, ec))
        if (f.path().extension() == ".gltf" || f.path().extension() == ".glb") found.push_back(f.path());
      std::sort(found.begin(), found.end());
      if (!found.empty()) {
        files.push_back(found.front().string());
        break;
      }
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

struct exr_pixels {
  int width = 0, height = 0;
  std::vector<float> rgba;  // 4 a pixel
  std::vector<float> object;
};

exr_pixels read_render(const std::string& path) {
  exr_pixels out;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return out;
  const OIIO::ImageSpec& spec = in->spec();
  out.width = spec.width;
  out.height = spec.height;
  std::vector<float> all(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data());
  const int object = spec.channelindex("id.object");
  const int channel[4] = {spec.channelindex("R"), spec.channelindex("G"), spec.channelindex("B"),
                          spec.channelindex("A")};
  for (size_t p = 0; p < size_t(spec.width) * size_t(spec.height); ++p) {
    for (int c = 0; c < 4; ++c) out.rgba.push_back(all[p * size_t(spec.nchannels) + size_t(channel[c])]);
    out.object.push_back(object >= 0 ? all[p * size_t(spec.nchannels) + size_t(object)] : 0.0f);
  }
  return out;
}

bool is_edge(const exr_pixels& im, int x, int y) {
  const size_t p = size_t(y) * size_t(im.width) + size_t(x);
  const float alpha = im.rgba[p * 4 + 3];
  if (alpha > 0.0f && alpha < 1.0f) return true;
  for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
    const int nx = x + dx, ny = y + dy;
    if (nx < 0 || ny < 0 || nx >= im.width || ny >= im.height) continue;
    if (im.object[size_t(ny) * size_t(im.width) + size_t(nx)] != im.object[p]) return true;
  }
  return false;
}

class shading_reference : public ::testing::TestWithParam<std::string> {};

TEST_P(shading_reference, wave_shading_stays_within_the_bound_of_the_reference) {
  const std::string file = GetParam();
  const std::string dir = testing::scratch_folder("shading_reference_" + fs::path(file).stem().string());
  auto render = [&](const std::string& mode) {
    const std::string out = dir + "/" + mode + ".exr";
    const testing::command_result r =
        testing::run_kiln({"render", file, "-o", out, "--width", "64", "--height", "48", "--spp", "4",
                           "--aovs", "beauty,id", "--float", "--shading", mode});
    return std::pair{r, out};
  };
  const auto [reference_run, reference_path] = render("reference");
  const auto [wave_run, wave_path] = render("wave");
  // Files kiln refuses (an extension it does not support) are refused the same way by both.
  ASSERT_EQ(wave_run.exit_code, reference_run.exit_code) << wave_run.stderr_text;
  if (reference_run.exit_code != 0) return;
  const exr_pixels reference = read_render(reference_path), wave = read_render(wave_path);
  ASSERT_EQ(reference.width, 64);
  ASSERT_EQ(wave.rgba.size(), reference.rgba.size());
  float low = 0.0f, high = 0.0f;
  for (float v : reference.rgba) low = std::min(low, v), high = std::max(high, v);
  const double range = std::max(double(high - low), 1e-3);
  double total = 0.0;
  int outliers = 0;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      const size_t p = size_t(y) * size_t(reference.width) + size_t(x);
      double worst = 0.0;
      for (size_t c = 0; c < 4; ++c) {
        const double d = std::abs(double(wave.rgba[p * 4 + c]) - double(reference.rgba[p * 4 + c]));
        total += d;
        worst = std::max(worst, d);
      }
      outliers += worst > 0.01 * range && !is_edge(reference, x, y);
    }
  EXPECT_LE(total / double(reference.rgba.size()), 1e-4 * range) << file;
  EXPECT_EQ(outliers, 0) << file;
}

INSTANTIATE_TEST_SUITE_P(scenes_and_assets, shading_reference, ::testing::ValuesIn(scene_files()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string name =
                               fs::path(param.param).stem().string() + "_" + std::to_string(param.index);
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace kiln
