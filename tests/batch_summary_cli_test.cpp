// kiln batch --summary is written whatever stops the batch, complete and in one piece: a plan
// refused, a job refused after planning (it writes into another batch's folder), a job that
// fails. The summary names the batch's error and exit code and lists every planned job.
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

// Runs a batch of manifest jobs (each {"asset", "output"}) on the demo scene with a summary in
// dir/report/summary.json; returns the run and the summary (null when none was written).
struct batch_run {
  command_result result;
  json summary;
};

batch_run run_with_summary(const fs::path& dir, const json& jobs) {
  testing::copy_scene((dir / "scenes").string());
  fs::create_directories(dir / "report");
  const std::string manifest = (dir / "jobs.json").string(),
                    summary = (dir / "report" / "summary.json").string();
  std::ofstream(manifest) << json({{"jobs", jobs}}).dump();
  batch_run run;
  run.result = run_kiln({"batch", "--manifest", manifest, "--out-dir", (dir / "out").string(), "--summary",
                         summary, "--width", "8", "--height", "6", "-q"});
  if (fs::exists(summary)) run.summary = json::parse(std::ifstream(summary));
  // Written in one piece: nothing but the summary beside it (no temporary left).
  for (const auto& entry : fs::directory_iterator(dir / "report"))
    EXPECT_EQ(entry.path().filename(), "summary.json");
  return run;
}

// The summary says the batch stopped with exit_code and error, every listed job not started.
void expect_stopped(const batch_run& run, int exit_code, size_t jobs) {
  EXPECT_EQ(run.result.exit_code, exit_code) << run.result.stderr_text;
  ASSERT_TRUE(run.summary.is_object()) << "no summary; stderr: " << run.result.stderr_text;
  EXPECT_EQ(run.summary["version"], 1);
  EXPECT_EQ(run.summary["exit_code"], exit_code);
  // The error is the line kiln printed, without its "kiln: ".
  EXPECT_EQ("kiln: " + run.summary["error"].get<std::string>() + "\n", run.result.stderr_text);
  ASSERT_EQ(run.summary["jobs"].size(), jobs);
  for (const json& job : run.summary["jobs"]) EXPECT_EQ(job["status"], "not_started");
  EXPECT_EQ(run.summary["totals"]["jobs"], jobs);
  EXPECT_EQ(run.summary["totals"]["not_started"], jobs);
  EXPECT_EQ(run.summary["totals"]["rendered"], 0);
}

TEST(batch_summary, a_refused_plan_leaves_a_summary_with_the_error) {
  const fs::path dir = testing::scratch_folder("batch_summary_refused_plan");
  const json same = {{"asset", "scenes/cornell_box.gltf"}, {"output", "a.exr"}};
  const batch_run run = run_with_summary(dir, {same, same});
  expect_stopped(run, 2, 0);
  EXPECT_NE(run.summary["error"].get<std::string>().find("writes " + (dir / "out" / "a.exr").string()),
            std::string::npos);
}

TEST(batch_summary, a_job_refused_after_planning_leaves_a_summary_listing_every_job) {
  const fs::path dir = testing::scratch_folder("batch_summary_refused_job");
  // Another batch is running in out/sub: a job writing there is refused once the folder is locked.
  fs::create_directories(dir / "out" / "sub");
  const int fd =
      ::open((dir / "out" / "sub" / ".kiln-batch.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  const std::string pid = std::to_string(::getpid()) + "\n";
  ASSERT_EQ(::write(fd, pid.data(), pid.size()), ssize_t(pid.size()));
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const batch_run run =
      run_with_summary(dir, {{{"asset", "scenes/cornell_box.gltf"}, {"output", "a.exr"}},
                             {{"asset", "scenes/cornell_box.gltf"}, {"output", "sub/b.exr"}}});
  ::close(fd);
  expect_stopped(run, 2, 2);
  EXPECT_NE(run.summary["error"].get<std::string>().find("is the output folder of another kiln batch"),
            std::string::npos);
  EXPECT_EQ(run.summary["jobs"][1]["output"], (dir / "out" / "sub" / "b.exr").string());
  EXPECT_FALSE(fs::exists(dir / "out" / "a.exr"));
}

TEST(batch_summary, a_batch_that_ran_has_no_error_in_its_summary) {
  const fs::path dir = testing::scratch_folder("batch_summary_ran");
  const batch_run run = run_with_summary(dir, {{{"asset", "scenes/cornell_box.gltf"}, {"output", "a.exr"}},
                                               {{"asset", "scenes/missing.gltf"}, {"output", "b.exr"}}});
  EXPECT_EQ(run.result.exit_code, 1) << run.result.stderr_text;
  ASSERT_TRUE(run.summary.is_object());
  EXPECT_TRUE(run.summary["error"].is_null());
  EXPECT_EQ(run.summary["exit_code"], 1);
  EXPECT_EQ(run.summary["jobs"][0]["status"], "rendered");
  EXPECT_EQ(run.summary["jobs"][1]["status"], "failed");
}

TEST(batch_summary, a_summary_inside_a_missing_out_dir_is_written_there) {
  const fs::path dir = testing::scratch_folder("batch_summary_in_out_dir");
  testing::copy_scene((dir / "scenes").string());
  const fs::path out = dir / "out", summary = out / "summary.json";
  const command_result result =
      run_kiln({"batch", (dir / "scenes" / "cornell_box.gltf").string(), "--out-dir", out.string(),
                "--summary", summary.string(), "--width", "8", "--height", "6", "-q"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  ASSERT_TRUE(fs::exists(summary)) << result.stderr_text;
  const json written = json::parse(std::ifstream(summary));
  EXPECT_EQ(written["exit_code"], 0);
  EXPECT_EQ(written["totals"]["rendered"], 1);
}

}  // namespace
}  // namespace kiln
