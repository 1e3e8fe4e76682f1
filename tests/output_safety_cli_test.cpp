// Outputs never destroy inputs, end to end through the binary: an output that is not .exr, that is
// the asset, a buffer or image it reads, the environment map or the preview (by path, hard link or
// symlink), or that is itself a symbolic link is refused with exit 2 before anything renders, and
// the file it names keeps its bytes. The same holds for kiln batch and kiln stitch.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using testing::command_result;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

const std::vector<std::string> tiny = {"--width", "12", "--height", "9", "-q"};

std::string copy_scene(const fs::path& folder, const std::string& name = "cornell_box.gltf") {
  return testing::copy_scene(folder.string(), name);
}

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

command_result render(const std::string& asset, std::vector<std::string> args) {
  args.insert(args.begin(), {"render", asset});
  args.insert(args.end(), tiny.begin(), tiny.end());
  return run_kiln(args);
}

// Exit 2 with one line holding every part of expected, and the file's bytes as they were.
void expect_refused(const command_result& result, const std::vector<std::string>& expected,
                    const fs::path& untouched, const std::string& bytes) {
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
  for (const std::string& part : expected)
    EXPECT_NE(result.stderr_text.find(part), std::string::npos)
        << "'" << part << "' not in " << result.stderr_text;
  EXPECT_TRUE(bytes_of(untouched) == bytes) << untouched << " changed";
}

TEST(output_safety, an_output_that_is_not_exr_is_refused_and_png_points_to_preview) {
  const fs::path folder = scratch_folder("safety_names");
  const std::string asset = copy_scene(folder);
  std::ofstream(folder / "x.png") << "a picture someone keeps";
  const std::string png = bytes_of(folder / "x.png");
  expect_refused(render(asset, {"-o", (folder / "x.png").string()}), {"x.png", ".exr", "--preview"},
                 folder / "x.png", png);
  for (const char* name : {"x.tif", "x", "x.exr.tmp"}) {
    auto result = render(asset, {"-o", (folder / name).string()});
    EXPECT_EQ(result.exit_code, 2) << name << ": " << result.stderr_text;
    EXPECT_NE(result.stderr_text.find("must end in .exr"), std::string::npos) << result.stderr_text;
    EXPECT_FALSE(fs::exists(folder / name)) << name;
  }
  // Case does not matter.
  EXPECT_EQ(render(asset, {"-o", (folder / "upper.EXR").string()}).exit_code, 0);
}

TEST(output_safety, an_output_that_is_an_input_is_refused_before_rendering) {
  const fs::path folder = scratch_folder("safety_inputs");
  const std::string asset = copy_scene(folder);
  const std::string asset_bytes = bytes_of(asset);
  // A hard link to the asset under an .exr name.
  fs::create_hard_link(asset, folder / "asset_link.exr");
  expect_refused(render(asset, {"-o", (folder / "asset_link.exr").string()}), {"the asset"}, asset,
                 asset_bytes);

  // A buffer whose URI ends in .exr, named directly and through a symlinked folder.
  nlohmann::json doc = nlohmann::json::parse(bytes_of(asset));
  doc["buffers"][0]["uri"] = "geometry.exr";
  std::ofstream(folder / "renamed.gltf") << doc.dump();
  fs::copy_file(folder / "cornell_box.bin", folder / "geometry.exr");
  const std::string buffer_bytes = bytes_of(folder / "geometry.exr");
  const std::string renamed = (folder / "renamed.gltf").string();
  expect_refused(render(renamed, {"-o", (folder / "geometry.exr").string()}), {"buffer or image file"},
                 folder / "geometry.exr", buffer_bytes);
  fs::create_directory_symlink(folder, folder / "same_folder");
  expect_refused(render(renamed, {"-o", (folder / "same_folder" / "geometry.exr").string()}),
                 {"buffer or image file"}, folder / "geometry.exr", buffer_bytes);

  // The environment map.
  const std::string env = (folder / "env.exr").string();
  ASSERT_EQ(render(asset, {"-o", env}).exit_code, 0);
  const std::string env_bytes = bytes_of(env);
  expect_refused(render(asset, {"--environment", env, "-o", env}), {"--environment"}, env, env_bytes);

  // A preview onto the texture the asset reads: nothing is written, not even the EXR.
  const std::string texture_bytes = bytes_of(folder / "checker.png");
  const std::string out = (folder / "out.exr").string();
  expect_refused(render(asset, {"-o", out, "--preview", (folder / "checker.png").string()}),
                 {"--preview", "buffer or image file"}, folder / "checker.png", texture_bytes);
  EXPECT_FALSE(fs::exists(out));

  // A preview that is the output itself (a hard link to it).
  ASSERT_EQ(render(asset, {"-o", out}).exit_code, 0);
  const std::string out_bytes = bytes_of(out);
  fs::create_hard_link(out, folder / "out_link.png");
  expect_refused(render(asset, {"-o", out, "--preview", (folder / "out_link.png").string()}),
                 {"--preview", "same file as the -o output"}, out, out_bytes);
}

// kiln refuses a symlink as output, dangling or not: replacing it by rename would silently turn it
// into a regular file and leave its target stale.
TEST(output_safety, a_symlink_output_is_refused_and_stays_a_symlink) {
  const fs::path folder = scratch_folder("safety_symlinks");
  const std::string asset = copy_scene(folder);
  fs::create_symlink(folder / "nowhere.exr", folder / "dangling.exr");
  auto result = render(asset, {"-o", (folder / "dangling.exr").string()});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("symbolic link"), std::string::npos) << result.stderr_text;
  EXPECT_TRUE(fs::is_symlink(folder / "dangling.exr"));
  EXPECT_FALSE(fs::exists(folder / "nowhere.exr"));

  const std::string target = (folder / "target.exr").string();
  ASSERT_EQ(render(asset, {"-o", target}).exit_code, 0);
  const std::string target_bytes = bytes_of(target);
  fs::create_symlink(target, folder / "link.exr");
  expect_refused(render(asset, {"-o", (folder / "link.exr").string()}), {"symbolic link", "target.exr"},
                 target, target_bytes);
  EXPECT_TRUE(fs::is_symlink(folder / "link.exr"));
  fs::create_symlink(folder / "picture.png", folder / "preview_link.png");
  result = render(
      asset, {"-o", (folder / "fine.exr").string(), "--preview", (folder / "preview_link.png").string()});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("symbolic link"), std::string::npos) << result.stderr_text;
  EXPECT_FALSE(fs::exists(folder / "fine.exr"));
}

TEST(output_safety, batch_outputs_that_are_not_exr_links_or_inputs_stop_the_batch_with_exit_2) {
  const fs::path folder = scratch_folder("safety_batch");
  const std::string asset = copy_scene(folder);
  const fs::path out = folder / "out";
  fs::create_directories(out);
  // A manifest output that is not .exr, and one that is a symlink.
  std::ofstream(folder / "png.json")
      << nlohmann::json({{"jobs", {{{"asset", asset}, {"output", "a.png"}}}}}).dump();
  auto result =
      run_kiln({"batch", "--manifest", (folder / "png.json").string(), "--out-dir", out.string(), "-q"});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("/jobs/0"), std::string::npos) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("must end in .exr"), std::string::npos) << result.stderr_text;
  fs::create_symlink(folder / "elsewhere.exr", out / "link.exr");
  std::ofstream(folder / "link.json")
      << nlohmann::json({{"jobs", {{{"asset", asset}, {"output", "link.exr"}}}}}).dump();
  result =
      run_kiln({"batch", "--manifest", (folder / "link.json").string(), "--out-dir", out.string(), "-q"});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("symbolic link"), std::string::npos) << result.stderr_text;
  EXPECT_TRUE(fs::is_symlink(out / "link.exr"));

  // The default output (the asset's stem in --out-dir) onto the environment map.
  const std::string env = (out / "cornell_box.exr").string();
  ASSERT_EQ(render(asset, {"-o", env}).exit_code, 0);
  const std::string env_bytes = bytes_of(env);
  expect_refused(run_kiln({"batch", asset, "--environment", env, "--out-dir", out.string(), "-q"}),
                 {"--environment"}, env, env_bytes);
  // One job's output onto another job's input: job 1 writes checker.exr, job 0 reads it.
  std::ofstream(folder / "cross.json")
      << nlohmann::json(
             {{"jobs",
               {{{"asset", asset}, {"overrides", {{"environment", (out / "checker.exr").string()}}}},
                {{"asset", asset}, {"output", "checker.exr"}}}}})
             .dump();
  ASSERT_EQ(render(asset, {"-o", (out / "checker.exr").string()}).exit_code, 0);
  const std::string cross_bytes = bytes_of(out / "checker.exr");
  expect_refused(
      run_kiln({"batch", "--manifest", (folder / "cross.json").string(), "--out-dir", out.string(), "-q"}),
      {"/jobs/1", "--environment"}, out / "checker.exr", cross_bytes);
  // Previews sit beside their EXR: an asset named after its own texture would overwrite it.
  const std::string checker_asset = copy_scene(folder, "checker.gltf");
  const std::string texture_bytes = bytes_of(folder / "checker.png");
  expect_refused(run_kiln({"batch", checker_asset, "--out-dir", folder.string(), "--preview", "x.png", "-q"}),
                 {"checker.png", "buffer or image file"}, folder / "checker.png", texture_bytes);
  EXPECT_FALSE(fs::exists(folder / "checker.exr"));
}

TEST(output_safety, stitch_refuses_an_output_that_is_an_input_a_link_or_not_exr) {
  const fs::path folder = scratch_folder("safety_stitch");
  const std::string asset = copy_scene(folder);
  const std::string band0 = (folder / "band0.exr").string(), band1 = (folder / "band1.exr").string();
  ASSERT_EQ(render(asset, {"-o", band0, "--band", "0/2"}).exit_code, 0);
  ASSERT_EQ(render(asset, {"-o", band1, "--band", "1/2"}).exit_code, 0);
  const std::string band0_bytes = bytes_of(band0);
  expect_refused(run_kiln({"stitch", band0, band0, band1}), {"band0.exr", "input"}, band0, band0_bytes);
  fs::create_hard_link(band1, folder / "band1_link.exr");
  const std::string band1_bytes = bytes_of(band1);
  expect_refused(run_kiln({"stitch", (folder / "band1_link.exr").string(), band0, band1}), {"input"}, band1,
                 band1_bytes);
  auto result = run_kiln({"stitch", (folder / "frame.png").string(), band0, band1});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("must end in .exr"), std::string::npos) << result.stderr_text;
  EXPECT_FALSE(fs::exists(folder / "frame.png"));
  fs::create_symlink(folder / "frame.exr", folder / "frame_link.exr");
  result = run_kiln({"stitch", (folder / "frame_link.exr").string(), band0, band1});
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("symbolic link"), std::string::npos) << result.stderr_text;
  EXPECT_FALSE(fs::exists(folder / "frame.exr"));
  EXPECT_EQ(run_kiln({"stitch", (folder / "frame.exr").string(), band0, band1}).exit_code, 0);
}

}  // namespace
}  // namespace kiln
