// Planning a sequence of `kiln batch` without rendering: the frames of a manifest entry are jobs
// that share its options, so each plans in a few hundred bytes (a copy of the render options per
// frame took 3.2 GB for a million), and each job's options are made again on demand.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/batch_command.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

// AddressSanitizer's redzones and quarantine multiply what a process holds (as in
// tests/frame_scale_cli_test.cpp).
#if defined(__SANITIZE_ADDRESS__)
constexpr long asan_overhead = 4;
#else
constexpr long asan_overhead = 1;
#endif

// The process's peak resident memory so far (VmHWM), in KiB; -1 when /proc cannot say.
long peak_resident_kib() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

// A fifth of the million frames a batch allows, so the test stays short: the checks of each
// frame's outputs (a stat or two each) take most of the time.
constexpr long long frames = 200000;

TEST(batch_plan, the_frames_of_a_sequence_share_their_entry_s_options) {
  const fs::path dir = fs::temp_directory_path() / ("kiln_batch_plan_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "shot.gltf") << R"({"asset": {"version": "2.0"}})";
  std::ofstream(dir / "jobs.json") << R"({"jobs": [{"asset": "shot.gltf", "frames": "1-)" << frames
                                   << R"(", "output": "shot.#######.exr"}]})";
  batch_options options;
  options.manifest = (dir / "jobs.json").string();
  options.out_dir = (dir / "out").string();

  const long before_kib = peak_resident_kib();
  ASSERT_GT(before_kib, 0);
  const std::vector<batch_job> jobs = plan_batch(options);
  const long grown_kib = peak_resident_kib() - before_kib;
  std::printf("%lld frames planned: peak resident memory grew by %ld KiB\n", frames, grown_kib);

  ASSERT_EQ(jobs.size(), size_t(frames));
  EXPECT_EQ(jobs.front().name, "shot.0000001");
  EXPECT_EQ(jobs.back().name, "shot.0200000");
  // Before: a full render_options per frame, 640 MB; after: the job records and, while planning,
  // the maps of outputs to their writers and of names taken, about 60 MB.
  EXPECT_LT(grown_kib, 160L * 1024 * asan_overhead);

  // Each job's own options are the frame's, made on demand from the shared entry.
  const render_options last = batch_job_options(jobs.back());
  EXPECT_EQ(last.frame, frames);
  EXPECT_TRUE(last.frames.empty());
  EXPECT_EQ(last.output, (dir / "out" / "shot.0200000.exr").string());
  EXPECT_EQ(batch_job_output(jobs.back()), last.output);
  EXPECT_EQ(jobs.front().entry, jobs.back().entry);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace kiln
