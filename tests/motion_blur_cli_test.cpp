// Motion blur end to end (`kiln render --shutter OPEN,CLOSE`): the alpha of a moving edge against
// its closed-form coverage under an orthographic camera that maps one world unit to 32 pixels
// (a sliding quad, a morph target's moving edge), a spinning square whose blurred area stays its
// own (and shrinks when two steps interpolate a rotation linearly), a sliding glTF camera over a
// still edge, a sliding sphere quadric, the same bytes for any thread count, tiling and band and
// from a batch manifest, a still scene unchanged by a shutter, and the refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "support/animated_gltf.h"
#include "support/channel_exr.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::add_camera;
using testing::animate;
using testing::channel_exr;
using testing::gltf_builder;
using testing::render_float_exr;
using testing::run_kiln;
using testing::scratch_folder;
using testing::sliding_and_morphing;
using testing::spinning;

constexpr int side = 64;
constexpr double pixels_per_unit = side / 2.0;  // xmag = ymag = 1
// Frame 3 at 5 fps is t = 0.4 s; the shutter -0.5,0.5 is open over 0.3..0.5 s.
const std::vector<std::string> blurred_frame = {"--fps",     "5",        "--frame", "3",
                                                "--shutter", "-0.5,0.5", "--spp",   "256"};
constexpr double shutter_open = 0.3, shutter_close = 0.5;

// The closed form: the share of pixel column px (world x over [a, a + w]) that the span
// [left(t), right(t)] covers, averaged over the open shutter (midpoint rule, 20000 times).
double column_coverage(int px, const std::function<double(double)>& left,
                       const std::function<double(double)>& right) {
  const double w = 1.0 / pixels_per_unit, a = -1.0 + px * w;
  const int n = 20000;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double t = shutter_open + (k + 0.5) / n * (shutter_close - shutter_open);
    sum += std::clamp(std::min(a + w, right(t)) - std::max(a, left(t)), 0.0, w) / w;
  }
  return sum / n;
}

// Checks rows [y0, y1) of the alpha channel against the closed form, column by column: each pixel
// within per_pixel (256 samples of an edge), each column's mean within per_column.
void expect_profile(const channel_exr& image, int y0, int y1, const std::function<double(double)>& left,
                    const std::function<double(double)>& right, int& partial) {
  const double per_pixel = 0.15, per_column = 0.025;
  for (int x = 0; x < side; ++x) {
    SCOPED_TRACE("column " + std::to_string(x));
    const double expected = column_coverage(x, left, right);
    double mean = 0.0;
    for (int y = y0; y < y1; ++y) {
      const float alpha = image.at(size_t(y) * side + size_t(x), "A");
      EXPECT_NEAR(alpha, expected, per_pixel) << "row " << y;
      mean += alpha;
    }
    mean /= (y1 - y0);
    EXPECT_NEAR(mean, expected, per_column);
    // Fully covered or empty columns are exact: every sample agrees.
    if (expected == 0.0 || expected == 1.0) {
      EXPECT_EQ(mean, expected);
    }
    partial += expected > 0.05 && expected < 0.95;
  }
}

TEST(motion_blur_cli, a_sliding_and_a_morphing_edge_blur_as_the_closed_form_says) {
  const std::string dir = scratch_folder("blur_slide_morph");
  const channel_exr image =
      render_float_exr(sliding_and_morphing(dir), dir + "/out.exr", side, side, blurred_frame);
  ASSERT_EQ(image.count(), size_t(side * side));
  int partial = 0;
  {
    SCOPED_TRACE("slider");  // rows 0..31: x from t - 1 to t
    expect_profile(
        image, 0, side / 2, [](double t) { return t - 1.0; }, [](double t) { return t; }, partial);
  }
  {
    SCOPED_TRACE("morph");  // rows 32..63: x from -1 to -0.5 + 1.5 t (the weight is t)
    expect_profile(
        image, side / 2, side, [](double) { return -1.0; }, [](double t) { return -0.5 + 1.5 * t; }, partial);
  }
  // Each moving edge spreads over several columns (6.4 and 9.6 pixels of motion).
  EXPECT_GE(partial, 18);
}

double alpha_sum(const channel_exr& image) {
  double sum = 0.0;
  for (size_t i = 0; i < image.count(); ++i) sum += image.at(i, "A");
  return sum;
}

TEST(motion_blur_cli, a_spinning_square_keeps_its_area_and_blurs_only_where_it_turns) {
  const std::string dir = scratch_folder("blur_spin");
  const std::string scene = spinning(dir);
  const channel_exr image = render_float_exr(scene, dir + "/out.exr", side, side, blurred_frame);
  ASSERT_EQ(image.count(), size_t(side * side));
  // A rotation keeps the area at every time: 1 unit² = 1024 pixels of alpha. Interpolating it as
  // matrices over a step that turns by θ scales the area by 2/3 + cos(θ)/3 on average. The 18° turn
  // takes 3 steps (9° apart) to stay within a quarter pixel halfway: 1019.8 pixels. The samples'
  // noise on the blurred rim is about 1 pixel. The shutter is open 0.2 s.
  const double area = pixels_per_unit * pixels_per_unit;
  auto interpolated_area = [&](int steps) {
    return area * (2.0 + std::cos(18.0 / (steps - 1) * M_PI / 180.0)) / 3.0;
  };
  EXPECT_EQ(image.spec.get_int_attribute("kiln/shutter_steps"), 3);
  EXPECT_NEAR(alpha_sum(image), interpolated_area(3), 3.0);
  EXPECT_FLOAT_EQ(image.spec.get_float_attribute("ExposureTime"), 0.2f);  // expTime, as OpenImageIO names it
  // Inside the inscribed circle every time covers the pixel, outside the circumscribed one none.
  int inside = 0, outside = 0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const double r = std::hypot(x + 0.5 - side / 2.0, y + 0.5 - side / 2.0) / pixels_per_unit;
      const float alpha = image.at(size_t(y) * side + size_t(x), "A");
      if (r < 0.5 - 0.75 / pixels_per_unit) {
        EXPECT_EQ(alpha, 1.0f) << x << "," << y;
        ++inside;
      } else if (r > std::sqrt(0.5) + 0.75 / pixels_per_unit) {
        EXPECT_EQ(alpha, 0.0f) << x << "," << y;
        ++outside;
      }
    }
  EXPECT_GT(inside, 500);
  EXPECT_GT(outside, 1500);
  // Fixed steps: two lose 1.6% (17 pixels), nine 0.03%.
  for (const int steps : {2, 9}) {
    std::vector<std::string> fixed = blurred_frame;
    fixed.insert(fixed.end(), {"--motion-steps", std::to_string(steps)});
    const channel_exr other = render_float_exr(scene, dir + "/steps.exr", side, side, fixed);
    EXPECT_EQ(other.spec.get_int_attribute("kiln/shutter_steps"), steps);
    EXPECT_NEAR(alpha_sum(other), interpolated_area(steps), 3.0) << steps << " steps";
  }
}

// The top-half quad of sliding_and_morphing held still, seen by a glTF camera sliding +1 in x a
// second: the edge blurs as if the quad slid the other way.
std::string still_quad_sliding_camera(const std::string& folder) {
  gltf_builder b;
  b.add_node({{"mesh", b.add_mesh({{-1, 0, 0}, {0, 0, 0}, {0, 1, 0}, {-1, 1, 0}}, {0, 1, 2, 0, 2, 3})}});
  animate(b, add_camera(b), "translation", {0, 0, 5}, {1, 0, 5});
  return b.write(folder + "/camera.gltf");
}

TEST(motion_blur_cli, a_sliding_camera_blurs_a_still_edge_the_other_way) {
  const std::string dir = scratch_folder("blur_camera");
  const channel_exr image =
      render_float_exr(still_quad_sliding_camera(dir), dir + "/out.exr", side, side, blurred_frame);
  ASSERT_EQ(image.count(), size_t(side * side));
  int partial = 0;
  // In the view the quad spans x from -1 - t to -t.
  expect_profile(
      image, 0, side / 2, [](double t) { return -1.0 - t; }, [](double t) { return -t; }, partial);
  EXPECT_GE(partial, 5);
  for (size_t i = size_t(side / 2) * side; i < image.count(); ++i) EXPECT_EQ(image.at(i, "A"), 0.0f) << i;
}

// A KILN_quadric sphere of radius 0.25 sliding +1 in x a second from (-0.5, 0.5): Embree moves its
// instance, and the user geometry takes each ray back to object space at the ray's time.
std::string sliding_sphere(const std::string& folder) {
  gltf_builder b;
  b.add_mesh({{0, 0, -9}, {0.01f, 0, -9}, {0, 0.01f, -9}}, {0, 1, 2});  // the builder needs a buffer
  b.doc["extensionsUsed"] = {"KILN_quadric"};
  b.doc["extensions"]["KILN_quadric"]["primitives"] = {{{"kind", "sphere"}, {"radius", 0.25}}};
  const int sphere =
      b.add_node({{"translation", {-0.5, 0.5, 0}}, {"extensions", {{"KILN_quadric", {{"primitive", 0}}}}}});
  animate(b, sphere, "translation", {-0.5f, 0.5f, 0}, {0.5f, 0.5f, 0});
  add_camera(b);
  return b.write(folder + "/sphere.gltf");
}

TEST(motion_blur_cli, a_sliding_sphere_quadric_keeps_its_area_and_blurs_along_its_path) {
  const std::string dir = scratch_folder("blur_sphere");
  const channel_exr image =
      render_float_exr(sliding_sphere(dir), dir + "/out.exr", side, side, blurred_frame);
  ASSERT_EQ(image.count(), size_t(side * side));
  const double r = 0.25;
  EXPECT_NEAR(alpha_sum(image), M_PI * r * r * pixels_per_unit * pixels_per_unit, 3.0);
  // Its centre runs over x -0.2..0 at y 0.5: on that row the pixels within x -0.22..0.02 are
  // covered at every time, and no pixel past x -0.48 or 0.28 is ever covered.
  const int row = int((1.0 - 0.5) * pixels_per_unit);
  int partial = 0;
  for (int x = 0; x < side; ++x) {
    const double centre = -1.0 + (x + 0.5) / pixels_per_unit;
    const float alpha = image.at(size_t(row) * side + size_t(x), "A");
    if (centre > -0.22 && centre < 0.02) {
      EXPECT_EQ(alpha, 1.0f) << x;
    }
    for (int y = 0; y < side && (centre < -0.48 || centre > 0.28); ++y)
      EXPECT_EQ(image.at(size_t(y) * side + size_t(x), "A"), 0.0f) << x;
    partial += alpha > 0.05f && alpha < 0.95f;
  }
  EXPECT_GE(partial, 8);  // 6.4 pixels of motion at each side
}

TEST(motion_blur_cli, the_image_is_the_same_for_any_thread_count_tiling_and_band) {
  const std::string dir = scratch_folder("blur_threads");
  const std::string scene = sliding_and_morphing(dir);
  std::vector<std::string> one = blurred_frame, two = blurred_frame;
  one.insert(one.end(), {"--threads", "1"});
  two.insert(two.end(), {"--threads", "2", "--tile-size", "7"});
  const channel_exr a = render_float_exr(scene, dir + "/one.exr", side, side, one);
  const channel_exr b = render_float_exr(scene, dir + "/two.exr", side, side, two);
  ASSERT_FALSE(a.pixels.empty());
  EXPECT_EQ(a.pixels, b.pixels);
  // A band of the frame (a farm task's share) holds the same bytes as those rows of the whole.
  std::vector<std::string> band = blurred_frame;
  band.insert(band.end(), {"--band", "1/2"});
  const channel_exr lower = render_float_exr(scene, dir + "/band.exr", side, side, band);
  ASSERT_EQ(lower.spec.y, side / 2);
  const size_t row = size_t(side) * size_t(a.spec.nchannels);
  ASSERT_EQ(lower.pixels.size(), row * size_t(side / 2));
  EXPECT_TRUE(
      std::equal(lower.pixels.begin(), lower.pixels.end(), a.pixels.begin() + row * size_t(side / 2)));
}

TEST(motion_blur_cli, a_batch_job_blurs_as_the_render_command_does) {
  const std::string dir = scratch_folder("blur_batch");
  const std::string scene = spinning(dir);
  const channel_exr alone = render_float_exr(scene, dir + "/alone.exr", side, side, blurred_frame);
  {
    std::ofstream manifest(dir + "/jobs.json");
    manifest << R"([{"asset": ")" << scene
             << R"(", "output": "spin.exr", "overrides": {"shutter": "-0.5,0.5", )"
             << R"("fps": 5, "frame": 3, "spp": 256, "float": true, "width": )" << side << R"(, "height": )"
             << side << "}}]";
  }
  const auto result = run_kiln({"batch", "--manifest", dir + "/jobs.json", "--out-dir", dir + "/out", "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const channel_exr batched{testing::read_float_exr(dir + "/out/spin.exr")};
  ASSERT_FALSE(alone.pixels.empty());
  EXPECT_EQ(batched.pixels, alone.pixels);
  const OIIO::ParamValue* shutter = batched.spec.find_attribute("kiln/shutter");  // a v2f
  ASSERT_NE(shutter, nullptr);
  ASSERT_EQ(shutter->type(), OIIO::TypeFloat2);
  EXPECT_EQ(static_cast<const float*>(shutter->data())[0], -0.5f);
  EXPECT_EQ(static_cast<const float*>(shutter->data())[1], 0.5f);
}

TEST(motion_blur_cli, a_still_scene_renders_the_same_with_a_shutter) {
  const std::string dir = scratch_folder("blur_still");
  const std::string scene = testing::copy_scene(dir);
  const channel_exr still = render_float_exr(scene, dir + "/still.exr", 48, 48, {"--spp", "4"});
  const channel_exr open =
      render_float_exr(scene, dir + "/open.exr", 48, 48, {"--spp", "4", "--shutter", "-1,1"});
  ASSERT_FALSE(still.pixels.empty());
  EXPECT_EQ(still.pixels, open.pixels);
}

TEST(motion_blur_cli, what_cannot_blur_is_refused_with_one_line) {
  const std::string dir = scratch_folder("blur_refused");
  const std::string scene = sliding_and_morphing(dir);
  const std::string out = dir + "/out.exr";
  struct refusal {
    std::vector<std::string> extra;
    std::string says;
  };
  const std::vector<refusal> refusals = {
      {{"--shutter", "0.5,-0.5"}, "--shutter: the shutter must open before it closes"},
      {{"--shutter", "0,nan"}, "--shutter: expects two finite frame offsets"},
      {{"--shutter", "-1,1", "--motion-steps", "1"}, "--motion-steps"},
      {{"--shutter", "-1,1", "--adaptive-threshold", "0.1"},
       "adaptive supersampling traces its corners at one time"},
      {{"--shutter", "-1,1", "--accel", "grid"}, "needs --accel embree"},
  };
  for (const refusal& r : refusals) {
    SCOPED_TRACE(r.says);
    std::vector<std::string> args = {"render", scene, "-o", out, "--fps", "5", "--frame", "3", "-q"};
    args.insert(args.end(), r.extra.begin(), r.extra.end());
    const auto result = run_kiln(args);
    EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find(r.says), std::string::npos) << result.stderr_text;
    EXPECT_EQ(testing::lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_FALSE(std::ifstream(out).good());
  }
}

}  // namespace
}  // namespace kiln
