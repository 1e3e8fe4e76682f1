// `kiln render --aovs` end to end: the channels each selection writes, their pixel formats, the
// header, and that the default is byte for byte the explicit `--aovs beauty,Z,N`.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

const std::string demo_scene = std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf";

// Renders the demo scene small into dir/name with extra arguments; fails the test on error.
std::string render(const std::string& dir, const std::string& name, std::vector<std::string> extra) {
  std::vector<std::string> args = {"render",   demo_scene, "-o", dir + "/" + name, "--width", "24",
                                   "--height", "18",       "-q", "--spp",          "2"};
  args.insert(args.end(), extra.begin(), extra.end());
  auto result = run_kiln(args);
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  return dir + "/" + name;
}

// Channel name -> pixel format as stored in the file.
std::map<std::string, OIIO::TypeDesc> channels(const std::string& path) {
  std::map<std::string, OIIO::TypeDesc> out;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return out;
  for (int c = 0; c < in->spec().nchannels; ++c)
    out[in->spec().channelnames[c]] = in->spec().channelformat(c);
  return out;
}

std::vector<std::string> names(const std::map<std::string, OIIO::TypeDesc>& m) {
  std::vector<std::string> out;
  for (const auto& [name, format] : m) out.push_back(name);
  return out;
}

TEST(exr_aov_cli, each_selection_writes_its_channels) {
  const std::string dir = scratch_folder("aov_channels");
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"beauty", {"A", "B", "G", "R"}},
      {"Z", {"Z"}},
      {"N", {"N.X", "N.Y", "N.Z"}},
      {"P", {"P.X", "P.Y", "P.Z"}},
      {"albedo", {"albedo.B", "albedo.G", "albedo.R"}},
      {"uv", {"uv.U", "uv.V"}},
      {"id", {"id.instance", "id.material", "id.object"}},
      {"id,beauty", {"A", "B", "G", "R", "id.instance", "id.material", "id.object"}},
  };
  for (const auto& [list, expected] : cases) {
    const std::string file = render(dir, "c.exr", {"--aovs", list});
    EXPECT_EQ(names(channels(file)), expected) << list;
    auto in = OIIO::ImageInput::open(file);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("kiln/aovs"), list == "id,beauty" ? "beauty,id" : list);
  }
}

TEST(exr_aov_cli, default_output_is_the_explicit_beauty_z_n) {
  const std::string dir = scratch_folder("aov_default");
  const std::string implicit = render(dir, "default.exr", {});
  const std::string explicit_list = render(dir, "explicit.exr", {"--aovs", "beauty,Z,N"});
  auto a = OIIO::ImageInput::open(implicit), b = OIIO::ImageInput::open(explicit_list);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->spec().channelnames, (std::vector<std::string>{"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z"}));
  EXPECT_EQ(a->spec().channelnames, b->spec().channelnames);
  EXPECT_EQ(a->spec().channelformats, b->spec().channelformats);
  EXPECT_EQ(a->spec().get_string_attribute("kiln/aovs"), "beauty,Z,N");
  // The pixels as stored (half and float), byte for byte.
  const size_t bytes = a->spec().image_bytes(true);
  ASSERT_EQ(bytes, b->spec().image_bytes(true));
  std::vector<unsigned char> pa(bytes), pb(bytes);
  ASSERT_TRUE(a->read_image(0, 0, 0, a->spec().nchannels, OIIO::TypeUnknown, pa.data()));
  ASSERT_TRUE(b->read_image(0, 0, 0, b->spec().nchannels, OIIO::TypeUnknown, pb.data()));
  EXPECT_EQ(std::memcmp(pa.data(), pb.data(), bytes), 0);
}

TEST(exr_aov_cli, depth_position_and_ids_stay_float_without_the_float_flag) {
  const std::string dir = scratch_folder("aov_formats");
  const std::string all = "beauty,Z,N,P,albedo,uv,id";
  for (const auto& [name, format] : channels(render(dir, "half.exr", {"--aovs", all}))) {
    // uv is float by default too (STMaps, UDIM tiles).
    const bool full = name == "Z" || name[0] == 'P' || name.rfind("id.", 0) == 0 || name.rfind("uv.", 0) == 0;
    EXPECT_EQ(format, full ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF) << name;
  }
  const auto floats = channels(render(dir, "float.exr", {"--aovs", all, "--float"}));
  EXPECT_EQ(floats.size(), 19u);
  for (const auto& [name, format] : floats) EXPECT_EQ(format, OIIO::TypeDesc::FLOAT) << name;
}

TEST(exr_aov_cli, ids_are_exact_integers_and_background_is_minus_one) {
  const std::string dir = scratch_folder("aov_ids");
  auto in = OIIO::ImageInput::open(render(dir, "ids.exr", {"--aovs", "id,Z", "--filter", "gaussian"}));
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(spec.image_pixels() * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  const int z = spec.channelindex("Z"), instance = spec.channelindex("id.instance");
  ASSERT_GE(z, 0);
  ASSERT_GE(instance, 0);
  std::set<float> instances;
  for (size_t p = 0; p < spec.image_pixels(); ++p) {
    const float* px = &pixels[p * spec.nchannels];
    for (const char* name : {"id.object", "id.material", "id.instance"}) {
      const float v = px[spec.channelindex(name)];
      EXPECT_EQ(v, std::round(v)) << name;
      if (std::isinf(px[z]))
        EXPECT_EQ(v, -1.0f) << name;
      else
        EXPECT_GE(v, 0.0f) << name;
    }
    instances.insert(px[instance]);
  }
  EXPECT_GE(instances.size(), 4u);  // the Cornell box's walls and blocks are separate instances
}

TEST(exr_aov_cli, header_records_standard_attributes_and_the_scene_hash) {
  const std::string dir = scratch_folder("aov_header");
  const std::string copy = dir + "/scene.gltf", changed = dir + "/changed.gltf";
  fs::copy_file(demo_scene, copy, fs::copy_options::overwrite_existing);
  fs::copy_file(demo_scene, changed, fs::copy_options::overwrite_existing);
  for (const char* resource : {"cornell_box.bin", "checker.png"})
    fs::copy_file(std::string(KILN_SOURCE_DIR) + "/scenes/" + resource, dir + "/" + resource,
                  fs::copy_options::overwrite_existing);
  std::ofstream(changed, std::ios::app) << ' ';  // same scene, different bytes
  auto hash_of = [&](const std::string& scene, const std::string& name) {
    auto result = run_kiln(
        {"render", scene, "-o", dir + "/" + name, "--width", "8", "--height", "6", "-q", "--spp", "3"});
    EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
    auto in = OIIO::ImageInput::open(dir + "/" + name);
    EXPECT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    const OIIO::ParamValue* seconds = spec.find_attribute("renderTimeSeconds", OIIO::TypeDesc::FLOAT);
    const OIIO::ParamValue* spp = spec.find_attribute("samplesPerPixel", OIIO::TypeDesc::INT);
    EXPECT_TRUE(seconds && *static_cast<const float*>(seconds->data()) >= 0.0f);
    EXPECT_TRUE(spp && *static_cast<const int*>(spp->data()) == 3);
    const std::string software = spec.get_string_attribute("Software");
    EXPECT_EQ(software.rfind("kiln ", 0), 0u) << software;
    return spec.get_string_attribute("kiln/scene_hash");
  };
  const std::string original = hash_of(demo_scene, "a.exr");
  EXPECT_EQ(original.size(), 16u);
  EXPECT_EQ(original.find_first_not_of("0123456789abcdef"), std::string::npos) << original;
  EXPECT_EQ(hash_of(copy, "b.exr"), original);
  EXPECT_NE(hash_of(changed, "c.exr"), original);
}

TEST(exr_aov_cli, unknown_or_repeated_aovs_exit_2_with_one_line) {
  for (const char* list : {"beauty,depth", "", "Z,Z", "beauty,"}) {
    auto result =
        run_kiln({"render", demo_scene, "-o", scratch_folder("aov_bad") + "/x.exr", "--aovs", list});
    EXPECT_EQ(result.exit_code, 2) << list;
    EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find("--aovs"), std::string::npos) << result.stderr_text;
  }
}

// The pixels of an EXR's data window as float, with the window.
struct exr_pixels {
  OIIO::ImageSpec spec;
  std::vector<float> values;
};

exr_pixels read_pixels(const std::string& path) {
  exr_pixels out;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return out;
  out.spec = in->spec();
  out.values.resize(out.spec.image_pixels() * out.spec.nchannels);
  in->read_image(0, 0, 0, out.spec.nchannels, OIIO::TypeDesc::FLOAT, out.values.data());
  return out;
}

TEST(exr_crop_cli, crop_stores_the_region_with_the_full_frame_as_display_window) {
  const std::string dir = scratch_folder("crop");
  const std::vector<std::string> common = {"--aovs",   "beauty,Z,N,P,id", "--filter",
                                           "gaussian", "--threads",       "2"};
  std::vector<std::string> crop_args = common;
  crop_args.insert(crop_args.end(), {"--crop", "5,4,17,13"});
  const exr_pixels full = read_pixels(render(dir, "full.exr", common));
  const exr_pixels crop = read_pixels(render(dir, "crop.exr", crop_args));
  EXPECT_EQ(crop.spec.x, 5);
  EXPECT_EQ(crop.spec.y, 4);
  EXPECT_EQ(crop.spec.width, 12);
  EXPECT_EQ(crop.spec.height, 9);
  EXPECT_EQ(crop.spec.full_x, 0);
  EXPECT_EQ(crop.spec.full_y, 0);
  EXPECT_EQ(crop.spec.full_width, 24);
  EXPECT_EQ(crop.spec.full_height, 18);
  EXPECT_EQ(full.spec.x, 0);
  EXPECT_EQ(full.spec.width, 24);
  ASSERT_EQ(crop.spec.channelnames, full.spec.channelnames);
  const int n = crop.spec.nchannels;
  int differing = 0;
  for (int y = 0; y < crop.spec.height; ++y)
    for (int x = 0; x < crop.spec.width; ++x)
      differing += std::memcmp(&crop.values[(size_t(y) * 12 + x) * n],
                               &full.values[(size_t(y + 4) * 24 + (x + 5)) * n], n * sizeof(float)) != 0;
  EXPECT_EQ(differing, 0);
}

TEST(exr_crop_cli, bad_crops_exit_2_with_one_line) {
  for (const char* crop : {"0,0,25,10", "3,3,3,9", "1,2,3", "-1,0,4,4", "0,0,4,19", "a,b,c,d"}) {
    auto result = run_kiln({"render", demo_scene, "-o", scratch_folder("crop_bad") + "/x.exr", "--width",
                            "24", "--height", "18", "--crop", crop});
    EXPECT_EQ(result.exit_code, 2) << crop;
    EXPECT_EQ(lines(result.stderr_text).size(), 1u) << result.stderr_text;
    EXPECT_NE(result.stderr_text.find("--crop"), std::string::npos) << result.stderr_text;
  }
}

}  // namespace
}  // namespace kiln
