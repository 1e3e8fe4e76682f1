// --working-space end to end, read back as a compositor would. Where colours do not multiply
// (white lights, one bounce), a linear Rec.709 render converted to ACEScg by the config's matrix
// equals the ACEScg render to float rounding, textured and untextured materials alike; where a
// coloured light meets a coloured surface they differ, because (M·a) ⊙ (M·b) ≠ M·(a ⊙ b): the
// test measures by how much, material by material. The EXR carries the space (chromaticities,
// colorspace, oiio:ColorSpace); without the option nothing changes; a sequence's frames equal
// single frames; bad configs and spaces are one line and exit 2 with nothing written, configs whose
// references loop, nest too deep or branch too widely for OpenColorIO included; the preview goes
// through OCIO only when asked.
#include <OpenColorIO/OpenColorIO.h>
#include <OpenEXR/ImfChromaticitiesAttribute.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "support/channel_exr.h"
#include "support/gltf_builder.h"
#include "support/kiln_process.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
namespace OCIO = OCIO_NAMESPACE;
using testing::run_kiln;
using testing::scratch_folder;

const std::string config = KILN_SOURCE_DIR "/share/ocio/kiln.ocio";
constexpr int size = 48;

// The cornell box copied into dir, edited by edit, written as name.
std::string cornell_variant(const std::string& dir, const std::string& name,
                            const std::function<void(nlohmann::json&)>& edit) {
  const std::string original = testing::copy_scene(dir);
  nlohmann::json gltf;
  std::ifstream(original) >> gltf;
  edit(gltf);
  const std::string path = dir + "/" + name;
  std::ofstream(path) << gltf.dump();
  return path;
}

// Every light white, and the glass's attenuation grey: nothing coloured multiplies anything else.
void whiten_lights(nlohmann::json& gltf) {
  for (auto& l : gltf["extensions"]["KHR_lights_punctual"]["lights"]) l["color"] = {1.0, 1.0, 1.0};
  for (auto& m : gltf["materials"])
    if (m.contains("extensions") && m["extensions"].contains("KHR_materials_volume"))
      m["extensions"]["KHR_materials_volume"]["attenuationColor"] = {0.9, 0.9, 0.9};
}

void drop_textures(nlohmann::json& gltf) {
  for (auto& m : gltf["materials"]) m["pbrMetallicRoughness"].erase("baseColorTexture");
}

// The config's linear Rec.709 -> ACEScg processor, read by the test itself (not through kiln).
OCIO::ConstCPUProcessorRcPtr rec709_to_acescg() {
  return OCIO::Config::CreateFromFile(config.c_str())
      ->getProcessor("Linear Rec.709 (sRGB)", "ACEScg")
      ->getDefaultCPUProcessor();
}

testing::channel_exr render(const std::string& scene, const std::string& path,
                            std::vector<std::string> extra) {
  extra.insert(extra.end(), {"--max-depth", "1", "--spp", "4", "--aovs", "beauty,id"});
  return testing::render_float_exr(scene, path, size, size, extra);
}

// The scene rendered twice: in linear Rec.709 (the default) and in ACEScg through kiln's config.
std::pair<testing::channel_exr, testing::channel_exr> rec709_and_acescg(const std::string& scene,
                                                                        const std::string& dir,
                                                                        std::vector<std::string> extra = {}) {
  std::vector<std::string> managed = extra;
  managed.insert(managed.end(), {"--ocio-config", config, "--working-space", "ACEScg"});
  return {render(scene, dir + "/rec709.exr", extra), render(scene, dir + "/acescg.exr", managed)};
}

// Per glTF material: the largest |converted Rec.709 − ACEScg| of R, G, B relative to max(|ACEScg|, 1e-3),
// the mean of it, and how many pixels it covers.
struct difference {
  float largest = 0.0f;
  double sum = 0.0;
  size_t pixels = 0;
};

std::map<int, difference> compare_by_material(const testing::channel_exr& rec709,
                                              const testing::channel_exr& acescg) {
  const OCIO::ConstCPUProcessorRcPtr convert = rec709_to_acescg();
  std::map<int, difference> out;
  const char* const rgb[3] = {"R", "G", "B"};
  for (size_t p = 0; p < rec709.count(); ++p) {
    float c[3] = {rec709.at(p, "R"), rec709.at(p, "G"), rec709.at(p, "B")};
    convert->applyRGB(c);
    float worst = 0.0f;
    for (int k = 0; k < 3; ++k) {
      const float reference = acescg.at(p, rgb[k]);
      worst = std::max(worst, std::abs(c[k] - reference) / std::max(std::abs(reference), 1e-3f));
    }
    difference& d = out[int(acescg.at(p, "id.material"))];
    d.largest = std::max(d.largest, worst);
    d.sum += worst;
    ++d.pixels;
  }
  return out;
}

// Float rounding: the renders' arithmetic in float32 on either side of the matrix, and the sRGB
// round trip of converted texels; measured at most 2e-6 (see the report printed below).
constexpr float tolerance = 1e-5f;

void expect_equal_within_rounding(const std::string& scene, const std::string& dir, const std::string& what,
                                  const std::vector<std::string>& extra = {}) {
  const auto [rec709, acescg] = rec709_and_acescg(scene, dir, extra);
  ASSERT_EQ(rec709.count(), acescg.count());
  EXPECT_EQ(rec709.spec.get_string_attribute("colorspace"), "");
  const std::map<int, difference> by_material = compare_by_material(rec709, acescg);
  // From outside the box (-1: the background) the camera sees the environment or background colour.
  const bool outside = std::find(extra.begin(), extra.end(), "--show-background") != extra.end();
  EXPECT_EQ(by_material.count(-1), outside ? 1u : 0u) << what;
  for (const auto& [material, d] : by_material) {
    std::printf("%s, material %d (%zu pixels): largest relative difference %.3g, mean %.3g\n", what.c_str(),
                material, d.pixels, double(d.largest), d.sum / double(d.pixels));
    EXPECT_LE(d.largest, tolerance) << what << ", material " << material;
  }
}

TEST(working_space_cli, white_light_rec709_converted_equals_the_acescg_render) {
  const std::string dir = scratch_folder("working_space_white");
  expect_equal_within_rounding(cornell_variant(dir, "white.gltf", whiten_lights), dir, "textured");
  const std::string plain = scratch_folder("working_space_white_plain");
  expect_equal_within_rounding(cornell_variant(plain, "plain.gltf",
                                               [](nlohmann::json& g) {
                                                 whiten_lights(g);
                                                 drop_textures(g);
                                               }),
                               plain, "untextured");
  // The environment map and the background colour are converted too: seen by camera rays from outside
  // the box, against white lights.
  const std::string sky = scratch_folder("working_space_white_sky");
  expect_equal_within_rounding(cornell_variant(sky, "white.gltf", whiten_lights), sky, "environment",
                               {"--environment", KILN_SOURCE_DIR "/scenes/glass_showcase_sky.hdr",
                                "--show-background", "--look-from", "0,1,9", "--look-at", "0,1,0"});
  const std::string background = scratch_folder("working_space_white_background");
  expect_equal_within_rounding(
      cornell_variant(background, "white.gltf", whiten_lights), background, "background",
      {"--background", "0.8,0.3,0.1", "--show-background", "--look-from", "0,1,9", "--look-at", "0,1,0"});
}

TEST(working_space_cli, coloured_light_on_coloured_surfaces_differs_where_colours_multiply) {
  // The box as shipped: a warm ceiling light (1, 0.95, 0.88) over red, green and white walls.
  const std::string dir = scratch_folder("working_space_coloured");
  const auto [rec709, acescg] = rec709_and_acescg(testing::copy_scene(dir), dir);
  float largest = 0.0f;
  for (const auto& [material, d] : compare_by_material(rec709, acescg)) {
    std::printf("coloured light, material %d (%zu pixels): largest relative difference %.3g, mean %.3g\n",
                material, d.pixels, double(d.largest), d.sum / double(d.pixels));
    largest = std::max(largest, d.largest);
  }
  EXPECT_GT(largest, 100 * tolerance);  // well past rounding: the products differ
}

TEST(working_space_cli, the_exr_is_tagged_with_the_working_space) {
  const std::string dir = scratch_folder("working_space_tags");
  const std::string scene = testing::copy_scene(dir);
  const std::string ap1 = dir + "/ap1.exr", plain = dir + "/plain.exr";
  ASSERT_EQ(run_kiln({"render", scene, "-o", ap1, "--width", "16", "--height", "16", "-q", "--ocio-config",
                      config, "--working-space", "ACEScg"})
                .exit_code,
            0);
  ASSERT_EQ(run_kiln({"render", scene, "-o", plain, "--width", "16", "--height", "16", "-q"}).exit_code, 0);
  {
    Imf::InputFile in(ap1.c_str());
    ASSERT_TRUE(Imf::hasChromaticities(in.header()));
    const Imf::Chromaticities c = Imf::chromaticities(in.header());
    EXPECT_EQ(c.red, Imath::V2f(0.713f, 0.293f));
    EXPECT_EQ(c.green, Imath::V2f(0.165f, 0.830f));
    EXPECT_EQ(c.blue, Imath::V2f(0.128f, 0.044f));
    EXPECT_EQ(c.white, Imath::V2f(0.32168f, 0.33767f));
    const auto* space = in.header().findTypedAttribute<Imf::StringAttribute>("colorspace");
    ASSERT_TRUE(space);
    EXPECT_EQ(space->value(), "ACEScg");
    const auto* oiio = in.header().findTypedAttribute<Imf::StringAttribute>("oiio:ColorSpace");
    ASSERT_TRUE(oiio);
    EXPECT_EQ(oiio->value(), "ACEScg");
    const auto* recorded = in.header().findTypedAttribute<Imf::StringAttribute>("kiln/working_space");
    ASSERT_TRUE(recorded);
    EXPECT_EQ(recorded->value(), "ACEScg");
    const auto* file = in.header().findTypedAttribute<Imf::StringAttribute>("kiln/ocio_config_file");
    ASSERT_TRUE(file);
    EXPECT_EQ(file->value(), config);
  }
  Imf::InputFile in(plain.c_str());
  const Imf::Chromaticities c = Imf::chromaticities(in.header());
  EXPECT_EQ(c.red, Imath::V2f(0.64f, 0.33f));
  EXPECT_EQ(c.white, Imath::V2f(0.3127f, 0.3290f));
  EXPECT_FALSE(in.header().findTypedAttribute<Imf::StringAttribute>("colorspace"));
  // OpenImageIO reads the tag back as the image's colour space.
  EXPECT_EQ(testing::read_float_exr(ap1).spec.get_string_attribute("oiio:ColorSpace"), "ACEScg");
}

TEST(working_space_cli, without_the_option_the_pixels_keep_every_bit) {
  // Naming linear Rec.709 through the config converts nothing: the pixels of the default render.
  const std::string dir = scratch_folder("working_space_default");
  const std::string scene = testing::copy_scene(dir);
  const auto plain = render(scene, dir + "/plain.exr", {});
  const auto named =
      render(scene, dir + "/named.exr", {"--ocio-config", config, "--working-space", "lin_rec709"});
  EXPECT_EQ(plain.pixels, named.pixels);
}

// A coloured quad with vertex colours whose right edge a morph target moves (so each pose builds it
// again), beside a still one with vertex colours (carried from frame to frame), under a coloured
// point light, seen by an orthographic camera: every kind of colour a sequence rebuilds or carries.
std::string animated_colours(const std::string& folder) {
  testing::gltf_builder b;
  const int material = b.add_material(
      {{"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.4, 0.2, 1.0}}, {"metallicFactor", 0.0}}}});
  const std::vector<float> colours = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 0};
  const int moving =
      b.add_mesh({{-1, -1, 0}, {-0.5f, -1, 0}, {-0.5f, 1, 0}, {-1, 1, 0}}, {0, 1, 2, 0, 2, 3}, material);
  const int still =
      b.add_mesh({{0.2f, -1, 0}, {1, -1, 0}, {1, 1, 0}, {0.2f, 1, 0}}, {0, 1, 2, 0, 2, 3}, material);
  for (int mesh : {moving, still})
    b.doc["meshes"][mesh]["primitives"][0]["attributes"]["COLOR_0"] = b.add_data(colours, 5126, "VEC3", 3);
  const int target =
      b.add_data(std::vector<float>{0, 0, 0, 0.6f, 0, 0, 0.6f, 0, 0, 0, 0, 0}, 5126, "VEC3", 3);
  b.doc["meshes"][moving]["primitives"][0]["targets"] = {{{"POSITION", target}}};
  b.doc["meshes"][moving]["weights"] = {0.0};
  const int morpher = b.add_node({{"mesh", moving}});
  b.add_node({{"mesh", still}});
  const int camera =
      b.add_camera({{"type", "orthographic"},
                    {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 100}}}});
  b.add_node({{"camera", camera}, {"translation", {0, 0, 5}}});
  const int light = b.add_light({{"type", "point"}, {"color", {0.3, 0.8, 1.0}}, {"intensity", 20.0}});
  b.add_node({{"translation", {0, 0, 2}}, {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}});
  const int times = b.add_data(std::vector<float>{0, 1}, 5126, "SCALAR", 1);
  const int weights = b.add_data(std::vector<float>{0, 1}, 5126, "SCALAR", 1);
  b.doc["animations"].push_back(
      {{"samplers", {{{"input", times}, {"output", weights}}}},
       {"channels", {{{"sampler", 0}, {"target", {{"node", morpher}, {"path", "weights"}}}}}}});
  return b.write(folder + "/animated.gltf");
}

TEST(working_space_cli, a_sequence_converts_each_frame_once_like_single_frames) {
  // Each frame's EXR is the one --frame N writes: what a pose builds again (the light, the morphed
  // mesh) is converted every frame, what it carries over (material, the still mesh) only once.
  const std::string dir = scratch_folder("working_space_sequence");
  const std::string scene = animated_colours(dir);
  const std::vector<std::string> managed = {"--ocio-config", config,  "--working-space",
                                            "ACEScg",        "--fps", "4"};
  std::vector<std::string> sequence = {"render",  scene,     "-o",       dir + "/seq_####.exr",
                                       "--width", "16",      "--height", "16",
                                       "-q",      "--float", "--frames", "1-3"};
  sequence.insert(sequence.end(), managed.begin(), managed.end());
  const auto result = run_kiln(sequence);
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  for (int frame = 1; frame <= 3; ++frame) {
    std::vector<std::string> single = managed;
    single.insert(single.end(), {"--frame", std::to_string(frame)});
    const auto alone = testing::render_float_exr(scene, dir + "/one.exr", 16, 16, single);
    const auto in_sequence =
        testing::channel_exr{testing::read_float_exr(dir + "/seq_000" + std::to_string(frame) + ".exr")};
    EXPECT_EQ(in_sequence.pixels, alone.pixels) << "frame " << frame;
    EXPECT_EQ(in_sequence.spec.get_string_attribute("colorspace"), "ACEScg");
  }
}

// Runs kiln with args; expects exit 2, one line naming `names`, and no output file.
void expect_refused(const std::vector<std::string>& args, const std::string& output,
                    const std::string& names) {
  const auto result = run_kiln(args);
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_EQ(testing::lines(result.stderr_text).size(), 1u) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find(names), std::string::npos) << result.stderr_text;
  EXPECT_FALSE(fs::exists(output)) << output;
}

TEST(working_space_cli, bad_configs_and_spaces_are_one_line_exit_2_nothing_written) {
  const std::string dir = scratch_folder("working_space_errors");
  const std::string scene = testing::copy_scene(dir);
  const std::string out = dir + "/out.exr";
  const std::vector<std::string> base = {"render", scene, "-o", out, "--width", "8", "--height", "8", "-q"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  expect_refused(with({"--ocio-config", config, "--working-space", "ACEScgg"}), out,
                 "kiln.ocio: --working-space: the config has no colour space 'ACEScgg'");
  expect_refused(with({"--ocio-config", config, "--working-space", "ACEScgx"}), out,
                 "the config has no colour space 'ACEScgx'; did you mean 'ACEScg'? (its colour spaces: "
                 "'ACES2065-1', 'ACEScg', 'Linear Rec.709 (sRGB)', 'sRGB - Display')\n");
  expect_refused(with({"--ocio-config", dir + "/none.ocio", "--working-space", "ACEScg"}), out,
                 "--ocio-config");
  const std::string broken = dir + "/broken.ocio";
  std::ofstream(broken) << "not: [a config\n";
  expect_refused(with({"--ocio-config", broken, "--working-space", "ACEScg"}), out,
                 "broken.ocio: --ocio-config: not a valid OpenColorIO config");
  expect_refused(with({"--ocio-config", broken}), out,
                 "broken.ocio: --ocio-config: not a valid OpenColorIO config");
  expect_refused(with({"--working-space", "ACEScg", "--preview", dir + "/p.png", "--display", "P3"}), out,
                 "--display: the config has no display 'P3'");
  ::setenv("OCIO", broken.c_str(), 1);
  expect_refused(with({"--working-space", "ACEScg"}), out,
                 "broken.ocio: $OCIO: not a valid OpenColorIO config");
  ::unsetenv("OCIO");
}

// The config `from` (kiln's by default) with its first `line` replaced by `with`, written as dir/name.
std::string config_variant(const std::string& dir, const std::string& name, const std::string& line,
                           const std::string& with, const std::string& from = config) {
  std::ifstream in(from);
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const size_t at = yaml.find(line);
  EXPECT_NE(at, std::string::npos) << line;
  if (at != std::string::npos) yaml.replace(at, line.size(), with);
  const std::string path = dir + "/" + name;
  std::ofstream(path) << yaml;
  return path;
}

// The start of ACEScg's matrix to the reference (ACES2065-1), the line a variant replaces.
const std::string acescg_to_reference =
    "    to_scene_reference: !<MatrixTransform> {matrix: [0.69545224135745176, 0.14067869647029421, "
    "0.16386906217225414, 0, 0.044794563372037771, 0.85967111845642197, 0.095534318171540414, 0, "
    "-0.0055258825581135434, 0.0040252103059786612, 1.0015006722521351, 0, 0, 0, 0, 1]}";

// Colour spaces c0 ... c<count - 1>, each converting to the reference through the next in `fan`
// ColorSpaceTransforms, the last (alias lin_rec709, glTF's space) a plain matrix.
std::string chain_config(const std::string& dir, const std::string& name, int count, int fan) {
  std::string yaml =
      "ocio_profile_version: 2\nroles:\n  default: c0\n  scene_linear: c0\n"
      "displays:\n  sRGB:\n    - !<View> {name: Raw, colorspace: c0}\ncolorspaces:\n";
  for (int i = 0; i < count; ++i) {
    yaml += "  - !<ColorSpace>\n    name: c" + std::to_string(i) + "\n";
    if (i + 1 == count) {
      yaml += "    aliases: [lin_rec709]\n    to_scene_reference: !<MatrixTransform> {}\n";
      continue;
    }
    std::string children;
    for (int k = 0; k < fan; ++k)
      children += std::string(k ? ", " : "") + "!<ColorSpaceTransform> {src: c" + std::to_string(count - 1) +
                  ", dst: c" + std::to_string(i + 1) + "}";
    yaml += "    to_scene_reference: !<GroupTransform> {children: [" + children + "]}\n";
  }
  const std::string path = dir + "/" + name;
  std::ofstream(path) << yaml;
  return path;
}

// Runs kiln with a deadline and, when stack_bytes is set, that stack limit: before the configs
// below were checked, OpenColorIO crashed or ran for hours on them, and neither may stop the suite.
testing::command_result run_kiln_at_most(const std::vector<std::string>& args, const std::string& dir,
                                         double seconds, rlim_t stack_bytes = 0) {
  const testing::child_process child = testing::start_kiln(args, dir, [stack_bytes] {
    if (!stack_bytes) return;
    const rlimit limit{stack_bytes, stack_bytes};
    ::setrlimit(RLIMIT_STACK, &limit);
  });
  const std::optional<int> code = child.wait_at_most(seconds);
  return {code ? *code : -1000, code ? child.stderr_text() : "still running after the deadline"};
}

void expect_refused_in_time(const std::vector<std::string>& args, const std::string& dir,
                            const std::string& names, rlim_t stack_bytes = 0) {
  const auto result = run_kiln_at_most(args, dir, 30.0, stack_bytes);
  EXPECT_EQ(result.exit_code, 2) << result.stderr_text;
  EXPECT_EQ(testing::lines(result.stderr_text).size(), 1u) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find(names), std::string::npos) << result.stderr_text;
}

TEST(working_space_cli, a_config_whose_references_loop_is_one_line_exit_2_not_a_crash) {
  const std::string dir = scratch_folder("working_space_loops");
  const std::string scene = testing::copy_scene(dir);
  const std::string out = dir + "/out.exr";
  auto render = [&](const std::string& cfg) {
    return std::vector<std::string>{
        "render",          scene,   "-o", out, "--width", "8", "--height", "8", "-q", "--ocio-config", cfg,
        "--working-space", "ACEScg"};
  };
  // ACEScg through a ColorSpaceTransform from itself.
  const std::string self =
      config_variant(dir, "self.ocio", acescg_to_reference,
                     "    to_scene_reference: !<ColorSpaceTransform> {src: ACEScg, dst: ACES2065-1}");
  expect_refused_in_time(render(self), dir,
                         "self.ocio: colour space 'ACEScg': its references loop back to it (colour space "
                         "'ACEScg' [to_scene_reference: ColorSpaceTransform src] -> colour space 'ACEScg')");
  // ACEScg to ACES2065-1 (by an alias, in a group) and back (by a role).
  std::string pair = config_variant(dir, "pair.ocio", acescg_to_reference,
                                    "    to_scene_reference: !<GroupTransform> {children: "
                                    "[!<ColorSpaceTransform> {src: lin_ap0, dst: lin_ap0}]}");
  pair = config_variant(dir, "pair.ocio", "    allocation: uniform\n\n  - !<ColorSpace>\n    name: ACEScg",
                        "    allocation: uniform\n    to_scene_reference: !<ColorSpaceTransform> "
                        "{src: compositing_linear, dst: ACES2065-1}\n\n  - !<ColorSpace>\n    name: ACEScg",
                        pair);
  expect_refused_in_time(
      render(pair), dir,
      "colour space 'ACES2065-1' [to_scene_reference: ColorSpaceTransform src] -> colour space 'ACEScg'");
  // Through a look whose process space is ACEScg itself.
  std::string look = config_variant(
      dir, "look.ocio", acescg_to_reference,
      "    to_scene_reference: !<LookTransform> {src: ACES2065-1, dst: ACES2065-1, looks: +grade}");
  look = config_variant(dir, "look.ocio", "\ncolorspaces:\n",
                        "\nlooks:\n  - !<Look>\n    name: grade\n    process_space: ACEScg\n"
                        "    transform: !<MatrixTransform> {}\n\ncolorspaces:\n",
                        look);
  expect_refused_in_time(render(look), dir, "look 'grade' [process_space] -> colour space 'ACEScg'");
  // The preview's view, from $OCIO: the sRGB display converts from the reference through itself.
  const std::string display =
      config_variant(dir, "display.ocio", "offset: [0.055, 0.055, 0.055, 0], direction: inverse}",
                     "offset: [0.055, 0.055, 0.055, 0], direction: inverse}\n"
                     "        - !<ColorSpaceTransform> {src: ACES2065-1, dst: srgb_display}");
  ::setenv("OCIO", display.c_str(), 1);
  expect_refused_in_time(
      {"render", scene, "-o", out, "--width", "8", "--height", "8", "-q", "--preview", dir + "/p.png"}, dir,
      "display.ocio: colour space 'sRGB - Display': its references loop back to it");
  ::unsetenv("OCIO");
  EXPECT_FALSE(fs::exists(out)) << out;
  // A batch's plan is made in one process: it is written, the job left to fail alone when it runs.
  ::setenv("OCIO", self.c_str(), 1);
  const auto planned = run_kiln_at_most({"batch", scene, "--out-dir", dir + "/batch", "--plan-only",
                                         dir + "/plan.json", "--working-space", "ACEScg"},
                                        dir, 30.0);
  ::unsetenv("OCIO");
  EXPECT_EQ(planned.exit_code, 0) << planned.stderr_text;
  EXPECT_TRUE(fs::exists(dir + "/plan.json"));
}

TEST(working_space_cli, references_nested_too_deep_or_branching_too_wide_are_refused_in_time) {
  const std::string dir = scratch_folder("working_space_deep");
  const std::string scene = testing::copy_scene(dir);
  auto render = [&](const std::string& cfg) {
    return std::vector<std::string>{
        "render", scene,           "-o", dir + "/out.exr",  "--width", "8", "--height",
        "8",      "--ocio-config", cfg,  "--working-space", "c0"};
  };
  // 600 colour spaces deep overflow a 1 MiB stack inside OpenColorIO (threads get less than 8 MiB).
  expect_refused_in_time(render(chain_config(dir, "deep.ocio", 600, 1)), dir,
                         "deep.ocio: colour space 'c0': its references nest more than 100 deep", 1 << 20);
  // 30 levels of two references each: OpenColorIO would follow 2^30 paths (2^20 take it 4 s).
  expect_refused_in_time(render(chain_config(dir, "wide.ocio", 30, 2)), dir,
                         "its references branch into more than 100000 paths");
  // A few levels and branches are fine.
  const auto small = run_kiln_at_most(render(chain_config(dir, "small.ocio", 8, 2)), dir, 30.0);
  EXPECT_EQ(small.exit_code, 0) << small.stderr_text;
}

// Reading and validating a looping config does not follow its references (only building a
// processor does), so kiln may read it before checking: run in a child, a crash fails the test.
TEST(working_space_cli, opencolorio_reads_and_validates_a_looping_config_without_recursing) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");  // the process has OpenImageIO's threads by now
  const std::string dir = scratch_folder("working_space_loop_read");
  const std::string self =
      config_variant(dir, "self.ocio", acescg_to_reference,
                     "    to_scene_reference: !<ColorSpaceTransform> {src: ACEScg, dst: ACES2065-1}");
  EXPECT_EXIT(
      {
        OCIO::Config::CreateFromFile(self.c_str())->validate();
        // Not exit(): a forked child would wait in log4cplus's finaliser for a thread it lacks.
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(working_space_cli, opencolorio_is_opened_only_when_a_render_names_a_working_space) {
  // With the colour module missing, everything but a colour-managed render still works.
  ::setenv("KILN_COLOUR_MODULE", "/nonexistent/kiln_colour.so", 1);
  const std::string dir = scratch_folder("working_space_lazy");
  const std::string scene = testing::copy_scene(dir);
  EXPECT_EQ(run_kiln({"--version"}).exit_code, 0);
  const std::vector<std::string> base = {"render",   scene, "-o", dir + "/out.exr", "--width", "8",
                                         "--height", "8",   "-q"};
  EXPECT_EQ(run_kiln(base).exit_code, 0);
  std::vector<std::string> managed = base;
  managed.insert(managed.end(), {"--working-space", "ACEScg"});
  const auto result = run_kiln(managed);
  ::unsetenv("KILN_COLOUR_MODULE");
  EXPECT_EQ(result.exit_code, 1) << result.stderr_text;
  EXPECT_EQ(testing::lines(result.stderr_text).size(), 1u) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("--working-space needs the colour module: /nonexistent/kiln_colour.so"),
            std::string::npos)
      << result.stderr_text;
}

// The PNG preview's 8-bit codes, read with OpenImageIO.
std::vector<unsigned char> preview_codes(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  if (!in) return {};
  std::vector<unsigned char> codes(in->spec().image_bytes());
  EXPECT_TRUE(in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::UINT8, codes.data()));
  return codes;
}

TEST(working_space_cli, the_preview_uses_the_configs_view_only_when_a_config_is_given) {
  ::unsetenv("OCIO");
  const std::string dir = scratch_folder("working_space_preview");
  const std::string scene = testing::copy_scene(dir);
  const std::vector<std::string> base = {"render", scene, "--width", "24", "--height", "24", "-q"};
  auto preview = [&](const std::string& name, std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), {"-o", dir + "/" + name + ".exr", "--preview", dir + "/" + name + ".png"});
    args.insert(args.end(), extra.begin(), extra.end());
    EXPECT_EQ(run_kiln(args).exit_code, 0) << name;
    return preview_codes(dir + "/" + name + ".png");
  };
  const auto exact = preview("exact", {});
  // kiln's config shows linear Rec.709 on sRGB through the same piecewise curve, in OCIO's float
  // arithmetic: a code may round the other way, no more.
  const auto ocio = preview("ocio", {"--ocio-config", config});
  // The ACEScg render shown through the config: back to Rec.709 by the inverse matrix first.
  const auto acescg = preview("acescg", {"--ocio-config", config, "--working-space", "ACEScg"});
  ASSERT_EQ(exact.size(), ocio.size());
  ASSERT_EQ(exact.size(), acescg.size());
  int worst = 0, worst_acescg = 0;
  for (size_t i = 0; i < exact.size(); ++i) {
    worst = std::max(worst, std::abs(int(exact[i]) - int(ocio[i])));
    worst_acescg = std::max(worst_acescg, std::abs(int(exact[i]) - int(acescg[i])));
  }
  EXPECT_LE(worst, 1);
  std::printf("preview codes: OCIO view vs exact curve differ by at most %d; ACEScg render's preview by %d\n",
              worst, worst_acescg);
  EXPECT_LE(worst_acescg, 4);
  // The config's Raw view shows the linear values themselves: far from the sRGB curve, so the view
  // named is the view applied.
  const auto raw = preview("raw", {"--ocio-config", config, "--view", "Raw"});
  ASSERT_EQ(raw.size(), exact.size());
  int worst_raw = 0;
  for (size_t i = 0; i < raw.size(); ++i)
    worst_raw = std::max(worst_raw, std::abs(int(exact[i]) - int(raw[i])));
  EXPECT_GT(worst_raw, 30);  // the light is warm: its products differ by about 2% (see the test above)
}

}  // namespace
}  // namespace kiln
