// What the command line says and stores, end to end: a mistyped option or command is named with
// the closest real one; text for an integer option is refused as not an integer; --multipart's help
// lists every part the writer can make; --channel-format sets the light split as --float does; uv
// is float by default; a stitched frame's renderTimeSeconds is the sum of its bands'.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

const std::string demo_scene = std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf";

// kiln's stdout (where CLI11 prints help) for arguments.
std::string kiln_stdout(const std::string& arguments) {
  const std::string file = scratch_folder("stdout") + "/out.txt";
  const std::string command =
      std::string("'") + KILN_BINARY + "' " + arguments + " > '" + file + "' 2>/dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Exit 2, one line, and every part of expected in it.
void expect_usage_error(const std::vector<std::string>& args, const std::vector<std::string>& expected) {
  const auto result = run_kiln(args);
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
  for (const std::string& part : expected)
    EXPECT_NE(result.stderr_text.find(part), std::string::npos)
        << "'" << part << "' not in " << result.stderr_text;
}

TEST(cli_messages, a_mistyped_option_suggests_the_closest_one) {
  const std::string out = scratch_folder("typo_option") + "/x.exr";
  // With -o missing too: the typo is the message, not the missing option.
  expect_usage_error({"render", demo_scene, "--widht", "100"},
                     {"unknown option --widht", "did you mean --width?"});
  expect_usage_error({"render", demo_scene, "-o", out, "--spp", "2", "--max-dpeth=3"},
                     {"--max-dpeth", "did you mean --max-depth?"});
  expect_usage_error({"batch", demo_scene, "--out-dir", out + ".d", "--resmue"}, {"did you mean --resume?"});
  expect_usage_error({"render", demo_scene, "-o", out, "--qqqqqqqq"}, {"unknown option --qqqqqqqq"});
  EXPECT_FALSE(fs::exists(out));
}

TEST(cli_messages, a_mistyped_manifest_option_suggests_the_closest_one) {
  const std::string dir = scratch_folder("typo_manifest");
  std::ofstream(dir + "/jobs.json")
      << nlohmann::json({{"jobs", {{{"asset", demo_scene}, {"overrides", {{"max-dept", 4}}}}}}}).dump();
  const auto result = run_kiln({"batch", "--manifest", dir + "/jobs.json", "--out-dir", dir + "/out"});
  EXPECT_EQ(result.exit_code, 1) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("unknown option --max-dept; did you mean --max-depth?"),
            std::string::npos)
      << result.stderr_text;
}

TEST(cli_messages, a_mistyped_command_suggests_the_closest_one) {
  expect_usage_error({"rendr", demo_scene}, {"unknown command 'rendr'", "did you mean 'render'?"});
  expect_usage_error({"stich", "a.exr", "b.exr"}, {"did you mean 'stitch'?"});
  expect_usage_error({"bacth"}, {"did you mean 'batch'?"});
  expect_usage_error({"paint"}, {"unknown command 'paint'", "render", "stitch"});
}

// Every integer option the help declares (INT or UINT), not a hand-kept list.
TEST(cli_messages, every_integer_option_says_an_integer_is_expected) {
  const std::string out = scratch_folder("integers") + "/x.exr";
  std::map<std::string, std::vector<std::string>> commands = {{"render", {"render", demo_scene, "-o", out}},
                                                              {"compare", {"compare", demo_scene}},
                                                              {"bench", {"bench", demo_scene}}};
  const std::regex integer_option(R"(^\s+(?:-\w,)?(--[\w-]+) U?INT\b)");
  size_t checked = 0;
  for (const auto& [name, prefix] : commands) {
    std::istringstream help(kiln_stdout(name + " --help"));
    for (std::string line; std::getline(help, line);) {
      std::smatch match;
      if (!std::regex_search(line, match, integer_option)) continue;
      const std::string option = match[1];
      std::vector<std::string> args = prefix;
      args.insert(args.end(), {option, "abc"});
      expect_usage_error(args, {option, "integer", "'abc'"});
      ++checked;
    }
  }
  EXPECT_GE(checked, 20u);  // --width, --spp, the limits, the grid and EXR options, --max-mismatches, ...
  // Numbers that are not integers, and negative text for an unsigned option.
  for (const char* bad : {"1.5", "12x", "1e3"})
    expect_usage_error({"render", demo_scene, "-o", out, "--spp", bad}, {"--spp: expects an integer", bad});
  expect_usage_error({"render", demo_scene, "-o", out, "--max-nodes", "-3"},
                     {"--max-nodes: expects a non-negative integer", "-3"});
  EXPECT_FALSE(fs::exists(out));
}

const std::vector<std::string> all_parts = {"rgba",
                                            "depth",
                                            "N",
                                            "P",
                                            "albedo",
                                            "uv",
                                            "id",
                                            "forward",
                                            "backward",
                                            "direct",
                                            "reflection",
                                            "refraction",
                                            "albedo_filtered",
                                            "N_filtered",
                                            "diffuse",
                                            "specular",
                                            "emission",
                                            "CryptoObject",
                                            "CryptoMaterial"};

std::vector<std::string> part_names(const std::string& path) {
  std::vector<std::string> names;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  for (int part = 0; in && in->seek_subimage(part, 0); ++part)
    names.push_back(in->spec().get_string_attribute("oiio:subimagename"));
  return names;
}

TEST(cli_messages, display_or_view_without_a_preview_warns_once_each_even_when_quiet) {
  const std::string dir = scratch_folder("display_without_preview");
  const std::vector<std::string> base = {"render",   demo_scene, "-o", dir + "/a.exr", "--width", "8",
                                         "--height", "6",        "-q"};
  auto with = [&base](const std::vector<std::string>& more) {
    std::vector<std::string> args = base;
    args.insert(args.end(), more.begin(), more.end());
    return run_kiln(args);
  };
  auto result = with({"--view", "Raw"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(result.stderr_text, "kiln: warning: --view does nothing without --preview\n");
  result = with({"--display", "sRGB", "--view", "Raw"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(result.stderr_text,
            "kiln: warning: --display does nothing without --preview\n"
            "kiln: warning: --view does nothing without --preview\n");
  // With a preview they choose its transform: nothing to say.
  result = with({"--display", "sRGB", "--view", "Raw", "--preview", dir + "/a.png"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(result.stderr_text, "");
  EXPECT_TRUE(fs::exists(dir + "/a.png"));
}

TEST(cli_messages, a_batch_says_view_without_a_preview_once_for_all_its_jobs) {
  const std::string dir = scratch_folder("batch_view_without_preview");
  const std::string one = testing::copy_scene(dir, "one.gltf"), two = testing::copy_scene(dir, "two.gltf");
  auto result = run_kiln(
      {"batch", one, two, "--out-dir", dir + "/out", "--width", "8", "--height", "6", "--view", "Raw", "-q"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(result.stderr_text, "kiln: warning: --view does nothing without --preview\n");
  EXPECT_TRUE(fs::exists(dir + "/out/two.exr"));
  // Each job's preview beside its EXR: the view is used.
  result = run_kiln({"batch", one, two, "--out-dir", dir + "/with", "--width", "8", "--height", "6", "--view",
                     "Raw", "--preview", "x.png", "-q"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(result.stderr_text, "");
  EXPECT_TRUE(fs::exists(dir + "/with/two.png"));
}

TEST(cli_messages, texture_cache_mb_is_accepted_with_one_deprecation_warning_and_not_offered) {
  const std::string dir = scratch_folder("texture_cache_mb");
  const auto result = run_kiln({"render", demo_scene, "-o", dir + "/a.exr", "--width", "8", "--height", "6",
                                "--texture-cache-mb", "64", "-q"});
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(
      result.stderr_text,
      "kiln: warning: --texture-cache-mb does nothing (kiln keeps every texture's mip pyramid in memory) "
      "and will be removed; drop it\n");
  EXPECT_TRUE(fs::exists(dir + "/a.exr"));
  EXPECT_EQ(kiln_stdout("render --help").find("texture-cache"), std::string::npos);
}

TEST(cli_messages, multipart_help_lists_every_part_the_writer_makes) {
  const std::string help = kiln_stdout("render --help");
  const size_t at = help.find("\n  --multipart");  // its own entry, not a mention in another
  ASSERT_NE(at, std::string::npos);
  const std::string entry = help.substr(at + 1, help.find('\n', at + 1) - at - 1);
  std::string listed;
  for (const std::string& part : all_parts) listed += (listed.empty() ? "" : ", ") + part;
  EXPECT_NE(entry.find("(" + listed + ")"), std::string::npos) << entry;
  // And those are the parts a render with every AOV writes, in that order.
  const std::string out = scratch_folder("every_part") + "/parts.exr";
  const auto result = run_kiln(
      {"render", demo_scene, "-o", out, "--width", "8", "--height", "6", "-q", "--multipart", "--aovs",
       "beauty,Z,N,P,albedo,uv,id,motion,direct,reflection,refraction,cryptomatte,albedo_filtered,N_filtered,"
       "diffuse,specular,emission"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_EQ(part_names(out), all_parts);
}

// Channel name -> format of a single-part EXR.
std::map<std::string, OIIO::TypeDesc> channel_formats(const std::string& path) {
  std::map<std::string, OIIO::TypeDesc> formats;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  if (!in) return formats;
  const OIIO::ImageSpec& spec = in->spec();
  for (int c = 0; c < spec.nchannels; ++c) formats[spec.channelnames[size_t(c)]] = spec.channelformat(c);
  return formats;
}

TEST(cli_messages, channel_format_sets_the_light_split_and_uv_is_float_by_default) {
  const std::string dir = scratch_folder("channel_formats");
  const std::vector<std::string> base = {"render", demo_scene, "--width",
                                         "8",      "--height", "6",
                                         "-q",     "--aovs",   "beauty,uv,direct,reflection,refraction"};
  auto render = [&](const std::string& name, std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), {"-o", dir + "/" + name + ".exr"});
    args.insert(args.end(), extra.begin(), extra.end());
    const auto result = run_kiln(args);
    EXPECT_EQ(result.exit_code, 0) << name << ": " << result.stderr_text;
    return channel_formats(dir + "/" + name + ".exr");
  };
  const OIIO::TypeDesc half = OIIO::TypeDesc::HALF, full = OIIO::TypeDesc::FLOAT;
  auto defaults = render("defaults", {});
  EXPECT_EQ(defaults["uv.U"], full);  // STMaps and UDIM tiles need more than half's 11 bits
  EXPECT_EQ(defaults["uv.V"], full);
  for (const char* c : {"R", "direct.R", "reflection.G", "refraction.B"}) EXPECT_EQ(defaults[c], half) << c;

  auto chosen = render("chosen", {"--channel-format", "direct=float,reflection=float,uv=half"});
  EXPECT_EQ(chosen["uv.U"], half);
  EXPECT_EQ(chosen["direct.R"], full);
  EXPECT_EQ(chosen["reflection.B"], full);
  EXPECT_EQ(chosen["refraction.G"], half);
  EXPECT_EQ(chosen["R"], half);

  auto all_float = render("all_float", {"--float", "--channel-format", "refraction=half"});
  EXPECT_EQ(all_float["direct.G"], full);
  EXPECT_EQ(all_float["refraction.G"], half);
  EXPECT_EQ(all_float["uv.V"], full);
}

float float_attribute(const std::string& path, const std::string& name) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  return in ? in->spec().get_float_attribute(name, -1.0f) : -1.0f;
}

TEST(cli_messages, a_stitched_frame_records_the_sum_of_its_bands_render_times) {
  const std::string dir = scratch_folder("stitch_times");
  std::vector<std::string> bands;
  std::vector<float> seconds;
  for (int i = 0; i < 3; ++i) {
    bands.push_back(dir + "/band" + std::to_string(i) + ".exr");
    const auto result = run_kiln({"render", demo_scene, "-o", bands.back(), "--width", "24", "--height", "18",
                                  "-q", "--spp", "4", "--band", std::to_string(i) + "/3"});
    ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
    seconds.push_back(float_attribute(bands.back(), "renderTimeSeconds"));
    EXPECT_GT(seconds.back(), 0.0f);
  }
  const std::string frame = dir + "/frame.exr";
  const auto result = run_kiln({"stitch", frame, bands[2], bands[0], bands[1]});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_FLOAT_EQ(float_attribute(frame, "renderTimeSeconds"), seconds[0] + seconds[1] + seconds[2]);
  auto in = OIIO::ImageInput::open(frame);
  ASSERT_TRUE(in);
  // Each band's own time, in the order the bands were given: a float vector, and the total a float.
  const OIIO::ParamValue* listed = in->spec().find_attribute("kiln/band_render_seconds");
  ASSERT_NE(listed, nullptr);
  EXPECT_EQ(listed->type().basetype, OIIO::TypeDesc::FLOAT);
  std::vector<float> read;
  for (int i = 0; i < int(listed->type().numelements()) * listed->type().aggregate; ++i)
    read.push_back(listed->get_float_indexed(i));
  EXPECT_EQ(read, (std::vector<float>{seconds[2], seconds[0], seconds[1]}));
  EXPECT_FLOAT_EQ(in->spec().get_float_attribute("kiln/render_seconds"),
                  seconds[0] + seconds[1] + seconds[2]);
  EXPECT_EQ(in->spec().find_attribute("kiln/render_seconds")->type(), OIIO::TypeFloat);
}

}  // namespace
}  // namespace kiln
