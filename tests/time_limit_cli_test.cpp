// --time-limit end to end: a render that would take minutes stops at its limit with exit 124 and
// one line, writes nothing and leaves an existing output as it was; a limit the render stays
// under changes nothing; the limit is not a pixel setting (the settings hash stays the same).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "support/float_exr.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

const std::string glass = std::string(KILN_SOURCE_DIR) + "/scenes/glass_showcase.gltf";

TEST(time_limit_cli, a_render_past_its_limit_stops_with_124_and_writes_nothing) {
  const std::string dir = scratch_folder("time_limit");
  const std::string out = dir + "/out.exr";
  std::ofstream(out) << "an older render";
  const auto start = std::chrono::steady_clock::now();
  // Minutes of work on two cores when left to finish.
  const auto result = run_kiln({"render", glass, "-o", out, "--width", "1600", "--height", "1200", "--spp",
                                "64", "--threads", "2", "--time-limit", "0.3"});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(result.exit_code, 124) << result.stderr_text;
  ASSERT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
  // The limit as it was given (0.3, not the double's 17 digits 0.29999999999999999).
  EXPECT_NE(result.stderr_text.find(out + ": time limit of 0.3 s reached, nothing written"),
            std::string::npos)
      << result.stderr_text;
  EXPECT_LT(seconds, 30.0);
  std::ifstream in(out);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "an older render");
  for (const auto& entry : fs::directory_iterator(dir)) EXPECT_EQ(entry.path().filename(), "out.exr");
}

TEST(time_limit_cli, a_limit_the_render_stays_under_changes_nothing) {
  const std::string dir = scratch_folder("time_limit_kept");
  const std::vector<std::string> base = {"render", glass, "--width", "32", "--height", "24", "-q"};
  auto with = base, without = base;
  with.insert(with.end(), {"-o", dir + "/with.exr", "--time-limit", "600"});
  without.insert(without.end(), {"-o", dir + "/without.exr"});
  ASSERT_EQ(run_kiln(with).exit_code, 0);
  ASSERT_EQ(run_kiln(without).exit_code, 0);
  const auto a = testing::read_float_exr(dir + "/with.exr");
  const auto b = testing::read_float_exr(dir + "/without.exr");
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_EQ(a.spec.get_string_attribute("kiln/settings_hash"),
            b.spec.get_string_attribute("kiln/settings_hash"));
  const auto bad = run_kiln({"render", glass, "-o", dir + "/x.exr", "--time-limit", "-1"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.stderr_text.find("--time-limit"), std::string::npos);
}

}  // namespace
}  // namespace kiln
