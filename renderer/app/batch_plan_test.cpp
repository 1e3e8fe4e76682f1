// Planning a sequence of `kiln batch` without rendering: the frames of a manifest entry are jobs
// that share its options, so each plans in under 200 bytes (a copy of the render options per
// frame took 3.2 GB for a million), and each job's options are made again on demand.
#include <gtest/gtest.h>
#include <malloc.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/batch_command.h"
#include "core/error.h"

#if defined(__SANITIZE_ADDRESS__)
// AddressSanitizer's runtime (sanitizer/allocator_interface.h, which GCC does not install).
extern "C" size_t __sanitizer_get_current_allocated_bytes();
#endif

namespace kiln {
namespace {

namespace fs = std::filesystem;

// The heap's bytes in use: AddressSanitizer's count of what the program asked for (its own
// redzones and quarantine left out), else glibc's, mmapped blocks included.
size_t heap_bytes_in_use() {
#if defined(__SANITIZE_ADDRESS__)
  return __sanitizer_get_current_allocated_bytes();
#else
  const struct mallinfo2 info = ::mallinfo2();
  return info.uordblks + info.hblkhd;
#endif
}

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

  const size_t heap_before = heap_bytes_in_use();
  const long peak_before_kib = peak_resident_kib();
  ASSERT_GT(peak_before_kib, 0);
  const std::vector<batch_job> jobs = plan_batch(options);
  const long peak_grown_kib = peak_resident_kib() - peak_before_kib;
  const double held_per_frame = double(heap_bytes_in_use() - heap_before) / double(frames);
  std::printf("%lld frames planned: %.0f bytes held a frame, peak resident memory grew by %ld KiB\n", frames,
              held_per_frame, peak_grown_kib);

  ASSERT_EQ(jobs.size(), size_t(frames));
  EXPECT_EQ(jobs.front().name, "shot.0000001");
  EXPECT_EQ(jobs.back().name, "shot.0200000");
  // Before: a full render_options per frame, about 3 KB held a frame and a peak of 650 MB; after:
  // the job records (64 bytes), and while planning the hashes of the files written and of the
  // names taken, a peak of about 36 MB. AddressSanitizer's quarantine keeps what planning frees
  // resident, so the peak is checked without it.
  EXPECT_LT(held_per_frame, 100.0);
#if !defined(__SANITIZE_ADDRESS__)
  EXPECT_LT(peak_grown_kib, 96L * 1024);
#endif

  // Each job's own options are the frame's, made on demand from the shared entry.
  const render_options last = batch_job_options(jobs.back());
  EXPECT_EQ(last.frame, frames);
  EXPECT_TRUE(last.frames.empty());
  EXPECT_EQ(last.output, (dir / "out" / "shot.0200000.exr").string());
  EXPECT_EQ(batch_job_output(jobs.back()), last.output);
  EXPECT_EQ(jobs.front().entry, jobs.back().entry);
  fs::remove_all(dir);
}

// The frames of two entries meet in one file (here the earlier's deep file): the later entry is
// refused naming the earlier, as two single jobs are; outputs that differ only in their extension's case get
// names of their own.
TEST(batch_plan, overlapping_sequences_are_refused_and_names_stay_unique) {
  const fs::path dir = fs::temp_directory_path() / ("kiln_batch_overlap_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "shot.gltf") << R"({"asset": {"version": "2.0"}})";
  batch_options options;
  options.out_dir = (dir / "out").string();
  options.manifest = (dir / "overlap.json").string();
  std::ofstream(options.manifest) << R"([{"asset": "shot.gltf", "frames": "1-3", "output": "s.####.exr"},
                                         {"asset": "shot.gltf", "frames": "4-9", "output": "s.####.exr",
                                          "overrides": {"deep": true}},
                                         {"asset": "shot.gltf", "frames": "9-12", "output": "s.####.deep.exr"}])";
  try {
    plan_batch(options);
    ADD_FAILURE() << "frame 9's deep file is written twice";
  } catch (const error& e) {
    EXPECT_EQ(std::string(e.what()), options.manifest + ": /2: writes " +
                                         (dir / "out/s.0009.deep.exr").string() + ", as does " +
                                         options.manifest + ": /1 (give one of them another output)");
  }

  options.manifest = (dir / "names.json").string();
  std::ofstream(options.manifest) << R"([{"asset": "shot.gltf", "output": "x.exr"},
                                         {"asset": "shot.gltf", "output": "x.EXR"},
                                         {"asset": "shot.gltf", "output": "x.Exr"},
                                         {"asset": "shot.gltf", "frames": "1-2", "output": "x.#.exr"}])";
  std::vector<std::string> names;
  for (const batch_job& job : plan_batch(options)) names.push_back(job.name);
  EXPECT_EQ(names, (std::vector<std::string>{"x", "x-2", "x-3", "x.1", "x.2"}));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace kiln
