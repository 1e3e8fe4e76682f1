// KHR_materials_variants end to end on the shared MaterialsVariantsShoe: --variant renders each
// colourway (the three differ in colour, not in coverage), an unknown one exits 2 naming the
// known ones, and a manifest job with "variants": "all" renders every colourway to its own output.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

const std::string shoe =
    std::string(KILN_SHARED_ASSETS) + "/MaterialsVariantsShoe/glTF/MaterialsVariantsShoe.gltf";

struct pixels {
  std::vector<float> rgba;
  std::string variant;
};

pixels read_rgba(const std::string& path) {
  pixels out;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return out;
  const OIIO::ImageSpec& spec = in->spec();
  out.rgba.resize(size_t(spec.width) * spec.height * 4);
  in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, out.rgba.data());
  out.variant = spec.get_string_attribute("kiln/variant");
  return out;
}

// The mean colour of the covered pixels, and how many there are.
std::vector<double> mean_colour(const pixels& p, size_t* covered) {
  std::vector<double> sum(3, 0.0);
  *covered = 0;
  for (size_t i = 0; i < p.rgba.size(); i += 4) {
    if (p.rgba[i + 3] < 1.0f) continue;
    ++*covered;
    for (int c = 0; c < 3; ++c) sum[c] += p.rgba[i + c];
  }
  for (double& s : sum) s /= double(std::max<size_t>(*covered, 1));
  return sum;
}

const std::vector<std::string> view = {"--width", "48", "--height", "48", "-q", "--threads", "2"};

TEST(variants_cli, each_variant_recolours_the_shoe_and_an_unknown_one_is_refused) {
  if (!std::filesystem::exists(shoe)) GTEST_SKIP() << "no sample assets";
  const std::string dir = scratch_folder("variants_render");
  std::vector<std::vector<double>> colours;
  std::vector<size_t> coverage;
  for (const char* variant : {"midnight", "beach", "street"}) {
    SCOPED_TRACE(variant);
    std::vector<std::string> args = {"render",    shoe,   "-o", dir + "/" + variant + ".exr",
                                     "--variant", variant};
    args.insert(args.end(), view.begin(), view.end());
    const auto result = run_kiln(args);
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    const pixels p = read_rgba(dir + "/" + variant + ".exr");
    EXPECT_EQ(p.variant, variant);
    size_t covered = 0;
    colours.push_back(mean_colour(p, &covered));
    coverage.push_back(covered);
    EXPECT_GT(covered, 100u);
  }
  // One shape, three colourways: the same pixels covered, clearly different mean colours.
  EXPECT_EQ(coverage[0], coverage[1]);
  EXPECT_EQ(coverage[1], coverage[2]);
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) {
      double distance = 0.0;
      for (int c = 0; c < 3; ++c)
        distance += std::abs(colours[size_t(a)][size_t(c)] - colours[size_t(b)][size_t(c)]);
      EXPECT_GT(distance, 0.02) << a << " vs " << b;
    }
  std::vector<std::string> bad = {"render", shoe, "-o", dir + "/bad.exr", "--variant", "forest"};
  bad.insert(bad.end(), view.begin(), view.end());
  const auto refused = run_kiln(bad);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(lines(refused.stderr_text).size(), 1u) << refused.stderr_text;
  EXPECT_NE(refused.stderr_text.find("no variant 'forest' (variants: 0 'midnight', 1 'beach', 2 'street')"),
            std::string::npos)
      << refused.stderr_text;
}

TEST(variants_cli, a_batch_job_with_all_variants_renders_every_colourway) {
  if (!std::filesystem::exists(shoe)) GTEST_SKIP() << "no sample assets";
  const std::string dir = scratch_folder("variants_batch");
  std::ofstream(dir + "/jobs.json") << nlohmann::json(
      {{"jobs", {{{"asset", shoe}, {"variants", "all"}, {"resolution", "48x48"}}}}});
  const auto result =
      run_kiln({"batch", "--manifest", dir + "/jobs.json", "--out-dir", dir + "/out", "-q", "--spp", "1"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  for (const char* variant : {"midnight", "beach", "street"}) {
    SCOPED_TRACE(variant);
    const pixels batch = read_rgba(dir + "/out/MaterialsVariantsShoe_" + variant + ".exr");
    EXPECT_EQ(batch.variant, variant);
    std::vector<std::string> args = {"render",    shoe,    "-o",      dir + "/single.exr",
                                     "--variant", variant, "--width", "48",
                                     "--height",  "48",    "-q"};
    ASSERT_EQ(run_kiln(args).exit_code, 0);
    EXPECT_EQ(batch.rgba, read_rgba(dir + "/single.exr").rgba);
  }
}

}  // namespace
}  // namespace kiln
