// Nodes that skin or morph one mesh alike render from one posed mesh: the same pixels as a file
// that gives every node a mesh and skin of its own, within a --max-memory that file's posed
// copies exceed (it is refused with one line before they are made), and through a sequence's
// frames, motion blur and motion vectors while the shared pose bends.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/deforming_strip.h"
#include "support/float_exr.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::add_strip_nodes;
using testing::bend_strip;
using testing::deforming_strip;
using testing::gltf_builder;
using testing::lines;
using testing::read_float_exr;
using testing::run_kiln;
using testing::scratch_folder;
using testing::unshared_poses;

// Every channel of every pixel of two renders, compared exactly.
void expect_same_pixels(const std::string& path, const std::string& reference) {
  SCOPED_TRACE(path);
  const testing::float_exr image = read_float_exr(path), expected = read_float_exr(reference);
  EXPECT_EQ(image.spec.channelnames, expected.spec.channelnames);
  ASSERT_EQ(image.pixels.size(), expected.pixels.size());
  size_t differ = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) differ += image.pixels[i] != expected.pixels[i];
  EXPECT_EQ(differ, 0u);
  EXPECT_GT(image.pixels.size(), 0u);
}

TEST(shared_poses_cli, one_posed_mesh_renders_like_a_copy_per_node_within_a_budget_the_copies_exceed) {
  const std::string dir = scratch_folder("shared_poses_budget");
  gltf_builder b = deforming_strip(10000);  // 20,000 triangles
  add_strip_nodes(b, 0, 20);                // one skin: one pose
  add_strip_nodes(b, 1, 20);                // the mesh's weights: one pose, placed 20 times
  const std::string shared = b.write(dir + "/shared.gltf");
  const std::string unshared = unshared_poses(b).write(dir + "/unshared.gltf");
  const std::vector<std::string> view = {"--width", "48", "--height", "36", "-q"};
  const auto render = [&](const std::string& scene, const std::string& out, const std::string& budget) {
    std::vector<std::string> args = {"render", scene, "-o", dir + "/" + out};
    args.insert(args.end(), view.begin(), view.end());
    if (!budget.empty()) args.insert(args.end(), {"--max-memory", budget});
    return run_kiln(args);
  };
  // 40 posed copies of 20,000 triangles need about 0.3 GB; the two shared poses fit in 64 MiB.
  const auto within = render(shared, "shared.exr", "64M");
  ASSERT_EQ(within.exit_code, 0) << within.stderr_text;
  const auto copies = render(unshared, "copies.exr", "64M");
  EXPECT_EQ(copies.exit_code, 2);
  ASSERT_EQ(lines(copies.stderr_text).size(), 1u) << copies.stderr_text;
  EXPECT_NE(copies.stderr_text.find(unshared), std::string::npos) << copies.stderr_text;
  EXPECT_NE(copies.stderr_text.find("posed meshes (one per distinct skin and morph pose) need about"),
            std::string::npos)
      << copies.stderr_text;
  const auto reference = render(unshared, "unshared.exr", "");
  ASSERT_EQ(reference.exit_code, 0) << reference.stderr_text;
  expect_same_pixels(dir + "/shared.exr", dir + "/unshared.exr");
}

TEST(shared_poses_cli, a_bending_shared_pose_blurs_and_moves_like_a_copy_per_node) {
  const std::string dir = scratch_folder("shared_poses_motion");
  gltf_builder b = deforming_strip(200);
  add_strip_nodes(b, 0, 4);
  add_strip_nodes(b, 1, 3);
  bend_strip(b);
  const std::string shared = b.write(dir + "/shared.gltf");
  const std::string unshared = unshared_poses(b).write(dir + "/unshared.gltf");
  for (const auto& [scene, name] : {std::pair{shared, "shared"}, std::pair{unshared, "unshared"}}) {
    const auto run = run_kiln({"render", scene, "-o", dir + "/" + name + "_####.exr", "--frames", "2-4",
                               "--fps", "4", "--shutter", "-0.5,0.5", "--spp", "4", "--aovs", "beauty,motion",
                               "--width", "32", "--height", "24", "-q"});
    ASSERT_EQ(run.exit_code, 0) << run.stderr_text;
  }
  for (const char* frame : {"0002", "0003", "0004"})
    expect_same_pixels(dir + "/shared_" + frame + ".exr", dir + "/unshared_" + frame + ".exr");
}

}  // namespace
}  // namespace kiln
