// The render job as a library call, without the binary: run_job's film matches its own crop, a
// raised cancel flag stops it before anything is written, warnings reach the callback, progress
// counts every pixel, and bad options fail before the scene loads.
#include "job/render_job.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "job/option_table.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

const std::string cornell = KILN_SOURCE_DIR "/scenes/cornell_box.gltf";

render_job small_job() {
  render_job job;
  job.options.input = cornell;
  for (auto [name, value] : {std::pair{"width", "24"}, {"height", "18"}, {"spp", "2"}, {"threads", "2"}})
    set_render_option(job.options, name, value);
  return job;
}

TEST(render_job, a_crop_holds_the_same_pixels_as_the_full_frame) {
  const render_job_result full = run_job(small_job());
  ASSERT_EQ(full.image.width, 24);
  render_job cropped = small_job();
  set_render_option(cropped.options, "crop", "5,4,17,11");
  const render_job_result part = run_job(cropped);
  ASSERT_EQ(part.image.width, 12);
  ASSERT_EQ(part.image.height, 7);
  float lit = 0.0f;
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 12; ++x) {
      const vec4& a = part.image.color[size_t(y) * 12 + size_t(x)];
      const vec4& b = full.image.color[size_t(y + 4) * 24 + size_t(x + 5)];
      EXPECT_EQ(a, b) << x << "," << y;
      lit += a.r;
    }
  EXPECT_GT(lit, 0.5f);  // not a black picture
  EXPECT_EQ(full.width, 24);
  EXPECT_EQ(part.width, 24);  // the frame, not the crop
}

TEST(render_job, progress_counts_every_pixel_and_metadata_records_the_options) {
  render_job job = small_job();
  render_progress progress;
  job.progress = &progress;
  const render_job_result r = run_job(job);
  EXPECT_EQ(progress.pixels_total.load(), 24u * 18u);
  EXPECT_EQ(progress.pixels_done.load(), 24u * 18u);
  std::map<std::string, exr_value> attributes(r.metadata.attributes.begin(), r.metadata.attributes.end());
  EXPECT_EQ(attributes["kiln/samples_per_pixel"], exr_value(2));
  EXPECT_EQ(std::get<std::string>(attributes["kiln/settings_hash"]).size(), 16u);
  // The shot's rate and first frame are recorded though not given; a still is no frame of a shot.
  EXPECT_EQ(attributes["kiln/fps"], exr_value(24.0));
  EXPECT_EQ(attributes["kiln/frame_start"], exr_value(1));
  EXPECT_FALSE(r.metadata.shot);
  EXPECT_EQ(r.stats.rays.camera, 24u * 18u * 2u);
}

TEST(render_job, a_raised_cancel_flag_stops_the_job_and_writes_nothing) {
  render_job job = small_job();
  job.options.output =
      (fs::temp_directory_path() / ("kiln_job_" + std::to_string(::getpid()) + ".exr")).string();
  std::atomic<bool> cancel{true};
  job.cancel = &cancel;
  try {
    run_job(job);
    FAIL() << "the job ran to the end";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::interrupted);
    EXPECT_FALSE(e.file().empty());  // what it was reading or writing when it stopped
  }
  EXPECT_FALSE(fs::exists(job.options.output));
}

TEST(render_job, warnings_reach_the_callback) {
  // One triangle and no light: under --lighting headlight the job adds the headlight, and says so.
  render_job job = small_job();
  job.options.lighting = "headlight";
  job.options.input =
      (fs::temp_directory_path() / ("kiln_job_" + std::to_string(::getpid()) + ".gltf")).string();
  std::ofstream(job.options.input) << R"({"asset": {"version": "2.0"},
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAAAAAAAAgD8AAAAA"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [-1, -1, 0], "max": [1, 1, 0]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})";
  std::vector<std::string> lines;
  job.warn = [&lines](const std::string& line) { lines.push_back(line); };
  const render_job_result r = run_job(job);
  fs::remove(job.options.input);
  EXPECT_GT(r.image.color[size_t(9) * 24 + 12].a, 0.0f);  // the triangle covers the centre
  ASSERT_FALSE(lines.empty());
  EXPECT_NE(lines.back().find("headlight"), std::string::npos) << lines.back();
}

TEST(render_job, bad_options_fail_before_the_scene_loads) {
  render_job job = small_job();
  job.options.input = "/nonexistent/never.gltf";
  set_render_option(job.options, "band", "0/2");
  set_render_option(job.options, "crop", "0,0,4,4");
  try {
    run_job(job);
    FAIL();
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::input);
    EXPECT_EQ(e.location(), "--crop");
  }
}

}  // namespace
}  // namespace kiln
