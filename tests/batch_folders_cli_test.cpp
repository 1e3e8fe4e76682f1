// What a batch may write: every job's output stays inside --out-dir (a manifest's "../x.exr", an
// absolute path elsewhere or a subfolder linked out of it is refused before anything renders).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::command_result;
using testing::run_kiln;
using testing::scratch_folder;

// A manifest of one Cornell box job with `output`, in dir/jobs.json.
std::string write_manifest(const fs::path& dir, const std::string& output) {
  testing::copy_scene((dir / "scenes").string());
  const std::string path = (dir / "jobs.json").string();
  std::ofstream(path)
      << json({{"jobs", {{{"asset", "scenes/cornell_box.gltf"}, {"output", output}}}}}).dump();
  return path;
}

command_result run_batch(const std::string& manifest, const fs::path& out_dir,
                         const std::string& extra = "") {
  std::vector<std::string> args = {"batch",   "--manifest", manifest,   "--out-dir", out_dir.string(),
                                   "--width", "8",          "--height", "6"};
  if (!extra.empty()) args.insert(args.end(), {"--plan-only", extra, "--no-estimates"});
  return run_kiln(args);
}

TEST(batch_folders, an_output_outside_the_out_dir_is_refused_naming_the_manifest_and_job) {
  const fs::path dir = scratch_folder("batch_escape");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  fs::create_directories(dir / "elsewhere");
  fs::create_symlink(dir / "elsewhere", out / "link");
  const struct {
    std::string output, resolved;
  } cases[] = {
      {"../x.exr", (dir / "x.exr").string()},
      {"sub/../../x.exr", (dir / "x.exr").string()},
      {(dir / "x.exr").string(), (dir / "x.exr").string()},
      {"link/x.exr", (dir / "elsewhere" / "x.exr").string()},
  };
  for (const auto& c : cases) {
    const std::string manifest = write_manifest(dir, c.output);
    const command_result result = run_batch(manifest, out);
    EXPECT_EQ(result.exit_code, 2) << c.output << ": " << result.stderr_text;
    EXPECT_EQ(result.stderr_text, "kiln: " + manifest + ": /jobs/0: output '" + c.output + "' resolves to '" +
                                      c.resolved + "', outside --out-dir '" + out.string() +
                                      "' (outputs stay inside the folder the batch locks)\n");
    EXPECT_FALSE(fs::exists(dir / "x.exr"));
    EXPECT_TRUE(fs::is_empty(dir / "elsewhere"));
  }
  // Inside the folder, by any spelling, is planned as given.
  for (const std::string& inside : {std::string("sub/../a.exr"), (out / "deep" / "a.exr").string()}) {
    const std::string plan = (dir / "plan.json").string();
    const command_result result = run_batch(write_manifest(dir, inside), out, plan);
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    EXPECT_EQ(json::parse(std::ifstream(plan))["jobs"][0]["output"],
              (out / fs::path(inside)).lexically_normal().string());
  }
}

}  // namespace
}  // namespace kiln
