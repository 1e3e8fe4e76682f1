// `kiln batch --resume` keeps an output only when every file of the job (EXR, deep EXR, preview)
// reads to its end, its header holds the job's hashes and its contents give the checksum recorded
// when it was written: a truncated file, flipped bytes of the same size, a header from other
// settings, an edited checksum or a missing deep file renders again, with the reason in the
// summary; an intact output is not touched.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::vector<char> bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
}

// Flips the byte `from_end` bytes before the end of path, keeping its size.
void flip_byte(const std::string& path, size_t from_end) {
  std::vector<char> bytes = bytes_of(path);
  ASSERT_GT(bytes.size(), from_end);
  bytes[bytes.size() - from_end] = char(bytes[bytes.size() - from_end] ^ 0x5A);
  write_bytes(path, bytes);
}

// The inode and modification time: a file rendered again is a new file renamed into place.
std::pair<ino_t, int64_t> identity(const std::string& path) {
  struct stat s {};
  EXPECT_EQ(::stat(path.c_str(), &s), 0) << path;
  return {s.st_ino, int64_t(s.st_mtim.tv_sec) * 1000000000 + s.st_mtim.tv_nsec};
}

// One job's batch, resumed: the asset's job in out/, with extra options.
struct resumed_batch {
  std::string dir, asset, out, summary, exr;
  explicit resumed_batch(const std::string& name) : dir(testing::scratch_folder(name)) {
    asset = testing::copy_scene(dir + "/scene");
    out = dir + "/out";
    summary = dir + "/summary.json";
    exr = out + "/cornell_box.exr";
  }
  // Runs the batch; returns the job's summary entry.
  json run(const std::vector<std::string>& extra = {}) const {
    std::vector<std::string> args = {"batch", asset, "--out-dir", out,  "--resume", "--summary",
                                     summary, "-q",  "--width",   "24", "--height", "18"};
    args.insert(args.end(), extra.begin(), extra.end());
    const testing::command_result r = testing::run_kiln(args);
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    std::ifstream in(summary);
    const json s = json::parse(in);
    return s["jobs"].at(0);
  }
};

// The job rendered again, and its summary line names the file and the reason.
void expect_rendered_because(const json& job, const std::string& file, const std::string& reason) {
  EXPECT_EQ(job["status"], "rendered");
  ASSERT_TRUE(job["resume"].is_string()) << job.dump();
  const std::string line = job["resume"];
  EXPECT_EQ(line.rfind(file + ": ", 0), 0u) << line;
  EXPECT_NE(line.find(reason), std::string::npos) << line;
  EXPECT_EQ(line.find('\n'), std::string::npos) << line;
}

TEST(resume_check_cli, an_intact_output_is_skipped_untouched_and_a_truncated_one_renders_again) {
  const resumed_batch b("resume_truncated");
  EXPECT_EQ(b.run()["status"], "rendered");
  const auto id = identity(b.exr);
  const json skipped = b.run();
  EXPECT_EQ(skipped["status"], "skipped");
  EXPECT_TRUE(skipped["resume"].is_null());
  EXPECT_EQ(identity(b.exr), id);

  fs::resize_file(b.exr, fs::file_size(b.exr) - 7);
  expect_rendered_because(b.run(), b.exr, "cannot be read to its end");
  EXPECT_NE(identity(b.exr), id);
  EXPECT_EQ(b.run()["status"], "skipped");
}

// Flipped bytes inside the pixel data of codecs that cannot detect them (PIZ, B44, DWAA: most of
// the corrupt files that used to be kept decoded to other pixels) keep the file's size and header.
// One part of R G B A in the codec (a lossy codec's part may hold no data layer).
TEST(resume_check_cli, flipped_pixel_bytes_render_again_under_every_codec) {
  const resumed_batch b("resume_flipped");
  for (const std::string codec : {"zip", "piz", "b44", "dwaa", "pxr24"}) {
    const std::vector<std::string> options = {"--compression", codec, "--aovs", "beauty"};
    EXPECT_EQ(b.run(options)["status"], "rendered") << codec;
    EXPECT_EQ(b.run(options)["status"], "skipped") << codec;
    const auto size = fs::file_size(b.exr);
    flip_byte(b.exr, 40);
    EXPECT_EQ(fs::file_size(b.exr), size);
    const json job = b.run(options);
    EXPECT_EQ(job["status"], "rendered") << codec;
    EXPECT_TRUE(job["resume"].is_string()) << codec;
    EXPECT_EQ(b.run(options)["status"], "skipped") << codec;
  }
}

TEST(resume_check_cli, a_header_from_other_settings_or_an_edited_checksum_renders_again) {
  const resumed_batch b("resume_header");
  EXPECT_EQ(b.run()["status"], "rendered");
  // Another render's EXR of the same frame size in its place: other settings (2 samples).
  const testing::command_result other = testing::run_kiln(
      {"render", b.asset, "-o", b.dir + "/other.exr", "--width", "24", "--height", "18", "--spp", "2", "-q"});
  ASSERT_EQ(other.exit_code, 0) << other.stderr_text;
  fs::copy_file(b.dir + "/other.exr", b.exr, fs::copy_options::overwrite_existing);
  expect_rendered_because(b.run(), b.exr, "kiln/settings_hash");

  // The recorded checksum edited (one hex digit): the pixels no longer match it.
  std::vector<char> bytes = bytes_of(b.exr);
  const std::string key = "kiln/checksum";
  const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
  ASSERT_NE(at, bytes.end());
  const std::string prefix = "crc32:";
  const auto value = std::search(at, bytes.end(), prefix.begin(), prefix.end());
  ASSERT_NE(value, bytes.end());
  char& digit = *(value + std::ptrdiff_t(prefix.size()));
  digit = digit == '0' ? '1' : '0';
  write_bytes(b.exr, bytes);
  expect_rendered_because(b.run(), b.exr, "not the recorded kiln/checksum");
  EXPECT_EQ(b.run()["status"], "skipped");
}

TEST(resume_check_cli, a_missing_truncated_or_flipped_deep_file_renders_again) {
  const resumed_batch b("resume_deep");
  const std::string deep = b.out + "/cornell_box.deep.exr";
  const std::vector<std::string> options = {"--deep"};
  EXPECT_EQ(b.run(options)["status"], "rendered");
  EXPECT_EQ(b.run(options)["status"], "skipped");
  fs::remove(deep);
  expect_rendered_because(b.run(options), deep, "missing");
  fs::resize_file(deep, 100);  // the case: skipped with exit 0 before
  expect_rendered_because(b.run(options), deep, "");
  const auto id = identity(b.exr);
  flip_byte(deep, 300);
  expect_rendered_because(b.run(options), deep, "");
  EXPECT_NE(identity(b.exr), id);  // the job renders all its files again
  EXPECT_EQ(b.run(options)["status"], "skipped");
}

// A JPEG has no checksum of its own, and a flipped byte in its scan decodes without complaint.
TEST(resume_check_cli, a_flipped_byte_in_a_preview_renders_again) {
  const resumed_batch b("resume_preview");
  for (const std::string format : {"jpg", "png"}) {
    const std::vector<std::string> options = {"--preview", "p." + format};
    const std::string preview = b.out + "/cornell_box." + format;
    EXPECT_EQ(b.run(options)["status"], "rendered") << format;
    EXPECT_EQ(b.run(options)["status"], "skipped") << format;
    flip_byte(preview, 100);
    expect_rendered_because(b.run(options), preview, "kiln/checksum");
    EXPECT_EQ(b.run(options)["status"], "skipped") << format;
  }
}

// A sequence's frames are checked one by one: only the damaged frame renders again (PIZ decodes a
// flipped byte without complaint).
TEST(resume_check_cli, only_the_damaged_frame_of_a_sequence_renders_again) {
  const resumed_batch b("resume_frames");
  const std::vector<std::string> options = {"--frames", "1-3", "--compression", "piz"};
  const auto run = [&] {
    b.run(options);
    std::ifstream in(b.summary);
    const json s = json::parse(in);
    std::vector<std::string> out;
    for (const json& job : s["jobs"]) out.push_back(job["status"]);
    return out;
  };
  EXPECT_EQ(run(), (std::vector<std::string>{"rendered", "rendered", "rendered"}));
  EXPECT_EQ(run(), (std::vector<std::string>{"skipped", "skipped", "skipped"}));
  const std::string frame2 = b.out + "/cornell_box.0002.exr";
  ASSERT_TRUE(fs::exists(frame2));
  flip_byte(frame2, 40);
  EXPECT_EQ(run(), (std::vector<std::string>{"skipped", "rendered", "skipped"}));
}

}  // namespace
}  // namespace kiln
