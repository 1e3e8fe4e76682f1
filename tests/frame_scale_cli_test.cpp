// A sequence of a hundred thousand frames costs its checks and its plan, not a parse of the asset
// and a probe file per frame, nor the whole plan or summary held at once: kiln render --frames
// checks every frame's outputs against the inputs it read once, and kiln batch writes its plan
// and summary a job at a time. Each run has a deadline and an address-space limit, so a
// regression fails here instead of stalling the suite.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/kiln_process.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::measured_run;

constexpr int frames = 100000;

// AddressSanitizer's shadow memory and quarantine take several times a process's own memory, and
// its checks several times the time: the peak RSS bounds and the deadline below are scaled by this
// under it (the deadline still fails the per-frame parse, 43 s in a release build).
#if defined(__SANITIZE_ADDRESS__)
constexpr long asan_overhead = 4;
#else
constexpr long asan_overhead = 1;
#endif

TEST(frame_scale, a_hundred_thousand_frames_are_checked_without_reading_the_asset_each_time) {
  const fs::path dir = testing::scratch_folder("frame_scale_render");
  const std::string asset = testing::copy_scene((dir / "scenes").string());
  fs::create_directories(dir / "out");
  // The first frame stops at once (--time-limit): what is measured is the check of every frame.
  const measured_run run =
      testing::run_measured({"render", asset, "-o", (dir / "out" / "shot.######.exr").string(), "--frames",
                             "1-" + std::to_string(frames), "--width", "4", "--height", "4", "--spp", "1",
                             "-q", "--time-limit", "0.000001"},
                            dir.string(), 25.0 * asan_overhead, uint64_t(2) << 30);
  std::printf("exit %d in %.2f s, peak %ld KiB\n", run.exit_code, run.seconds, run.peak_kib);
  // Before: about 43 s (a parse of the asset and a probe file per frame), killed at the deadline;
  // after: about 5 s on a 2-core machine, a stat or two per frame.
  EXPECT_EQ(run.exit_code, 124) << run.stderr_text;
  EXPECT_NE(run.stderr_text.find("shot.000001.exr: time limit"), std::string::npos) << run.stderr_text;
  EXPECT_LT(run.peak_kib, 256 * 1024 * asan_overhead);
  EXPECT_TRUE(fs::is_empty(dir / "out"));  // no probe file left behind
}

TEST(frame_scale, a_plan_of_a_hundred_thousand_frames_is_written_a_job_at_a_time) {
  const fs::path dir = testing::scratch_folder("frame_scale_plan");
  testing::copy_scene((dir / "scenes").string());
  const std::string manifest = (dir / "jobs.json").string(), plan = (dir / "plan.json").string();
  std::ofstream(manifest) << json({{"jobs",
                                    {{{"asset", "scenes/cornell_box.gltf"},
                                      {"frames", "1-" + std::to_string(frames)},
                                      {"output", "shot.######.exr"}}}}})
                                 .dump();
  const measured_run run =
      testing::run_measured({"batch", "--manifest", manifest, "--out-dir", (dir / "out").string(),
                             "--plan-only", plan, "--no-estimates"},
                            dir.string(), 120.0, uint64_t(3) << 30);
  std::printf("exit %d in %.2f s, peak %ld KiB\n", run.exit_code, run.seconds, run.peak_kib);
  ASSERT_EQ(run.exit_code, 0) << run.stderr_text;
  // Before: 1.6 GB for the plan's JSON tree and text; the jobs themselves, 300 MB while each held
  // a copy of the render options, are about 20 MB since the frames share them.
  EXPECT_LT(run.peak_kib, 700 * 1024 * asan_overhead);
  const json written = json::parse(std::ifstream(plan));
  ASSERT_EQ(written["jobs"].size(), size_t(frames));
  EXPECT_EQ(written["version"], 1);
  EXPECT_EQ(written["jobs"][0]["name"], "shot.000001");
  EXPECT_EQ(written["jobs"][frames - 1]["output"], (dir / "out" / "shot.100000.exr").string());
  // The text is what dump(2) of the whole plan gives.
  std::ifstream in(plan);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_EQ(text, written.dump(2) + "\n");
}

}  // namespace
}  // namespace kiln
