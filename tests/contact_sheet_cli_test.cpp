// `kiln batch --contact-sheet` end to end: after the jobs, one PNG (or JPEG) with a cell per job in a
// grid of the size docs/batch.md states, each good job's render in its box over the backdrop and its name
// under it, a failed job's box dark red with a red cross; a batch stopped early or a bad sheet
// name writes none, and a bad name is refused with one line and exit 2 before anything renders.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::gltf_builder;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

// A unit cube at the origin (kiln's default camera and studio environment see it).
std::string write_cube(const std::string& path) {
  gltf_builder b;
  std::vector<std::array<float, 3>> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back({i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f});
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<uint32_t> indices;
  for (const auto& q : quads) indices.insert(indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  b.add_node({{"mesh", b.add_mesh(corners, indices)}});
  return b.write(path);
}

struct rgb_image {
  int width = 0, height = 0, channels = 0;
  std::vector<unsigned char> codes;
  std::array<int, 3> at(int x, int y) const {
    const unsigned char* p = &codes[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels)];
    return {p[0], p[1], p[2]};
  }
};

rgb_image read_image(const std::string& path) {
  rgb_image image;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  if (!in) return image;
  image.width = in->spec().width;
  image.height = in->spec().height;
  image.channels = in->spec().nchannels;
  image.codes.resize(size_t(image.width) * size_t(image.height) * size_t(image.channels));
  EXPECT_TRUE(in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::UINT8, image.codes.data()));
  return image;
}

bool is_red(const std::array<int, 3>& c) { return c[0] > 180 && c[1] < 80 && c[2] < 80; }

// 32x24 renders: the box is 32x24, a cell 72 (the 64-pixel minimum and 4 on each side) by 24 +
// 8 + 12, and three jobs make two columns and two rows.
constexpr int cell_width = 72, cell_height = 44, box_width = 32, box_height = 24;

// The top-left corner of job k's box.
std::array<int, 2> box_of(int k) {
  return {(k % 2) * cell_width + (cell_width - box_width) / 2, (k / 2) * cell_height + 4};
}

TEST(contact_sheet_cli, a_batch_sheet_is_a_grid_of_renders_with_the_failed_job_crossed_out) {
  const std::string dir = scratch_folder("contact_sheet");
  const std::string cube = write_cube(dir + "/cube.gltf");
  write_cube(dir + "/other.gltf");
  std::ofstream(dir + "/jobs.csv") << "asset,output\ncube.gltf,\nother.gltf,\nmissing.gltf,\n";
  const auto result = run_kiln({"batch", "--manifest", dir + "/jobs.csv", "--out-dir", dir + "/out",
                                "--width", "32", "--height", "24", "--spp", "1", "--contact-sheet",
                                dir + "/sheet.png", "--summary", dir + "/summary.json"});
  EXPECT_EQ(result.exit_code, 1) << result.stderr_text;  // the missing asset fails its job
  EXPECT_NE(result.stderr_text.find("contact sheet -> " + dir + "/sheet.png"), std::string::npos)
      << result.stderr_text;
  const rgb_image sheet = read_image(dir + "/sheet.png");
  ASSERT_EQ(sheet.width, 2 * cell_width);
  ASSERT_EQ(sheet.height, 2 * cell_height);
  ASSERT_EQ(sheet.channels, 3);

  // The failed job (the third cell): a red cross along both diagonals of its box, none elsewhere.
  const auto [fx, fy] = box_of(2);
  for (double t : {0.1, 0.2, 0.8, 0.9}) {
    SCOPED_TRACE(t);
    EXPECT_TRUE(is_red(sheet.at(fx + int(t * box_width), fy + int(t * box_height))));
    EXPECT_TRUE(is_red(sheet.at(fx + int(t * box_width), fy + box_height - 1 - int(t * box_height))));
  }
  // Between the arms (above the "failed" plate) the box is dark red, not the sheet's grey.
  const std::array<int, 3> between = sheet.at(fx + box_width / 2, fy + 2);
  EXPECT_GT(between[0], between[1] + 20) << between[0] << "," << between[1];
  // The rendered jobs: the cube in the middle of the box, lit, and no red anywhere in their cells.
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE(k);
    const auto [x0, y0] = box_of(k);
    const std::array<int, 3> middle = sheet.at(x0 + box_width / 2, y0 + box_height / 2);
    EXPECT_GT(middle[0] + middle[1] + middle[2], 3 * 60);
    for (int y = (k / 2) * cell_height; y < (k / 2 + 1) * cell_height; ++y)
      for (int x = (k % 2) * cell_width; x < (k % 2 + 1) * cell_width; ++x)
        EXPECT_FALSE(is_red(sheet.at(x, y)));
  }
  // Each name under its box: light text in the label strip of every cell.
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    int lit = 0;
    for (int y = (k / 2) * cell_height + 4 + box_height + 4; y < (k / 2 + 1) * cell_height; ++y)
      for (int x = (k % 2) * cell_width; x < (k % 2 + 1) * cell_width; ++x) lit += sheet.at(x, y)[0] > 150;
    EXPECT_GT(lit, 10);
  }
  // The empty fourth cell is the sheet's background.
  EXPECT_EQ(sheet.at(cell_width + 4, cell_height + 4), (std::array<int, 3>{24, 24, 24}));

  // A JPEG sheet of two jobs: one row; the sheet inside --out-dir, which the batch creates.
  std::ofstream(dir + "/two.csv") << "asset,output\ncube.gltf,a.exr\n" << cube << ",b.exr\n";
  const auto jpeg =
      run_kiln({"batch", "--manifest", dir + "/two.csv", "--out-dir", dir + "/out2", "--width", "32",
                "--height", "24", "--spp", "1", "--contact-sheet", dir + "/out2/sheet.jpg", "-q"});
  ASSERT_EQ(jpeg.exit_code, 0) << jpeg.stderr_text;
  const rgb_image small = read_image(dir + "/out2/sheet.jpg");
  EXPECT_EQ(small.width, 2 * cell_width);
  EXPECT_EQ(small.height, cell_height);
}

TEST(contact_sheet_cli, bad_sheets_exit_2_with_one_line_before_anything_renders) {
  const std::string dir = scratch_folder("contact_sheet_errors");
  const std::string cube = write_cube(dir + "/cube.gltf");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--contact-sheet", dir + "/sheet.gif"}, "must end in .png, .jpg or .jpeg"},
      {{"--contact-sheet", dir + "/sheet.png", "--plan-only", dir + "/plan.json"}, "a plan renders nothing"},
      {{"--contact-sheet", dir + "/out/cube.png", "--preview", "x.png"}, "is also written by"},
  };
  for (const auto& [extra, says] : cases) {
    SCOPED_TRACE(says);
    std::vector<std::string> args = {"batch",   cube, "--out-dir", dir + "/out",
                                     "--width", "8",  "--height",  "6"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto result = run_kiln(args);
    EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
    EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find(says), std::string::npos) << result.stderr_text;
    EXPECT_FALSE(std::filesystem::exists(dir + "/out/cube.exr"));
  }
}

}  // namespace
}  // namespace kiln
