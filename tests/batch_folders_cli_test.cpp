// What a batch may write: every job's output stays inside --out-dir (a manifest's "../x.exr", an
// absolute path elsewhere or a subfolder linked out of it is refused before anything renders), and
// a running batch's lock covers its folder's subtree (a batch inside it is refused, and so is a
// job writing into another batch's folder inside its own).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

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

// Holds the batch lock on folder as a running batch does: its pid in the lock file, flock held.
struct held_lock {
  int fd = -1;
  explicit held_lock(const fs::path& folder) {
    fs::create_directories(folder);
    fd = ::open((folder / ".kiln-batch.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    const std::string pid = std::to_string(::getpid()) + "\n";
    EXPECT_EQ(::write(fd, pid.data(), pid.size()), ssize_t(pid.size()));
    EXPECT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  }
  ~held_lock() { ::close(fd); }
};

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

TEST(batch_folders, a_batch_inside_a_running_batchs_folder_is_refused) {
  const fs::path dir = scratch_folder("batch_nested_lock");
  const held_lock running(dir / "out");
  const fs::path inner = dir / "out" / "sub";
  const command_result result = run_batch(write_manifest(dir, "a.exr"), inner);
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_EQ(result.stderr_text,
            "kiln: " + inner.string() + ": the output folder lies inside " + (dir / "out").string() +
                ", the output folder of another kiln batch (pid " + std::to_string(::getpid()) +
                ") that is still running; wait for it to finish, give another --out-dir, or "
                "pass --wait-for-lock\n");
  EXPECT_FALSE(fs::exists(inner / "a.exr"));
  EXPECT_FALSE(fs::exists(inner / ".kiln-batch.lock"));
}

TEST(batch_folders, a_job_writing_into_another_batchs_folder_inside_its_own_is_refused) {
  const fs::path dir = scratch_folder("batch_lock_below");
  const fs::path out = dir / "out";
  const held_lock running(out / "sub");
  const std::string manifest = write_manifest(dir, "sub/a.exr");
  const command_result result = run_batch(manifest, out);
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_EQ(result.stderr_text,
            "kiln: " + manifest + ": /jobs/0: " + (out / "sub" / "a.exr").string() + ": the folder " +
                (out / "sub").string() + " is the output folder of another kiln batch (pid " +
                std::to_string(::getpid()) + ") that is still running; write elsewhere or wait for it\n");
  EXPECT_FALSE(fs::exists(out / "sub" / "a.exr"));
  // Beside the other batch's folder, not in it, the job renders.
  const command_result beside = run_batch(write_manifest(dir, "b.exr"), out);
  EXPECT_EQ(beside.exit_code, 0) << beside.stderr_text;
  EXPECT_TRUE(fs::exists(out / "b.exr"));
}

}  // namespace
}  // namespace kiln
