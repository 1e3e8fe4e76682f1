// Optional asset pixels: the glTF sample models that test one feature each are rendered through
// the CLI, and the pixels their READMEs describe (in ../shared/assets/<Model>/README.md) are
// checked: each assertion is one that the README's failure picture would break. Objects are found
// by glTF node (or mesh) name and projected with the EXR's worldToNDC, not by hand-picked pixels.
// Skips when the assets folder is absent.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "core/format_number.h"
#include "io/gltf/gltf_loader.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path asset(const std::string& relative) { return fs::path(KILN_SHARED_ASSETS) / relative; }

#define SKIP_WITHOUT_ASSETS()                     \
  if (!fs::is_directory(KILN_SHARED_ASSETS)) {    \
    GTEST_SKIP() << "../shared/assets is absent"; \
  }

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The glTF JSON of a .gltf, or of a .glb's first chunk (length at bytes 12..15, text from 20).
json gltf_json(const fs::path& file) {
  std::string bytes = read_bytes(file);
  if (file.extension() == ".glb") {
    uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    bytes = bytes.substr(20, length);
  }
  return json::parse(bytes);
}

// Writes a .glb with new JSON and the original binary chunk (images embedded there travel along).
void write_glb(const fs::path& original, const json& doc, const fs::path& out) {
  std::string bytes = read_bytes(original);
  uint32_t json_length = 0;
  std::memcpy(&json_length, bytes.data() + 12, 4);
  std::string rest = bytes.substr(20 + json_length);
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  std::string glb = "glTF" + u32(2) + u32(uint32_t(12 + 8 + text.size() + rest.size())) +
                    u32(uint32_t(text.size())) + "JSON" + text + rest;
  std::ofstream(out, std::ios::binary) << glb;
}

struct rgb {
  float r = 0, g = 0, b = 0;
  float luma() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
};

// Pixel rectangle [x0, x1) × [y0, y1), y down.
struct rect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  // Part of this rectangle by fractions of its width and height (0,0 = top left).
  rect part(double fx0, double fy0, double fx1, double fy1) const {
    return {int(std::lround(x0 + fx0 * width())), int(std::lround(y0 + fy0 * height())),
            int(std::lround(x0 + fx1 * width())), int(std::lround(y0 + fy1 * height()))};
  }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

std::ostream& operator<<(std::ostream& os, const rect& r) {
  return os << "[" << r.x0 << "," << r.y0 << " .. " << r.x1 << "," << r.y1 << ")";
}

// One kiln render: R G B A Z N.X N.Y N.Z and the header's worldToNDC.
struct rendering {
  int width = 0, height = 0;
  std::vector<float> pixels;
  float world_to_ndc[16] = {};

  const float* at(int x, int y) const { return &pixels[(size_t(y) * width + x) * 8]; }
  rgb color(int x, int y) const { return {at(x, y)[0], at(x, y)[1], at(x, y)[2]}; }
  float depth(int x, int y) const { return at(x, y)[4]; }

  // Pixel position of a world point (OpenEXR: row vectors, ndc_h = (p,1)·M, then the homogeneous
  // divide; NDC (0, 0) is the frame's upper-left corner and (1, 1) its lower-right).
  glm::dvec2 project(const dvec3& p) const {
    const float* m = world_to_ndc;
    double h[4];
    for (int c = 0; c < 4; ++c) h[c] = p.x * m[c] + p.y * m[4 + c] + p.z * m[8 + c] + m[12 + c];
    return {h[0] / h[3] * width, h[1] / h[3] * height};
  }
};

rendering render(const fs::path& file, const std::string& name, int width, int height,
                 std::vector<std::string> extra = {}) {
  std::string out = testing::scratch_folder("pixels_" + name) + "/out.exr";
  std::vector<std::string> args = {
      "render",   file.string(),          "-o",        out, "--width", std::to_string(width),
      "--height", std::to_string(height), "--threads", "2", "-q",      "--lighting",
      "headlight"};
  args.insert(args.end(), extra.begin(), extra.end());
  auto result = testing::run_kiln(args);
  EXPECT_EQ(result.exit_code, 0) << result.stderr_text;
  rendering r;
  auto in = OIIO::ImageInput::open(out);
  if (!in) {
    ADD_FAILURE() << "cannot read " << out;
    return r;
  }
  const OIIO::ImageSpec& spec = in->spec();
  EXPECT_EQ(spec.nchannels, 8);
  r.width = spec.width;
  r.height = spec.height;
  r.pixels.resize(size_t(r.width) * r.height * 8);
  EXPECT_TRUE(in->read_image(0, 0, 0, 8, OIIO::TypeDesc::FLOAT, r.pixels.data()));
  const OIIO::ParamValue* m = spec.find_attribute("worldToNDC", OIIO::TypeMatrix44);
  EXPECT_TRUE(m) << "no worldToNDC in " << out;
  if (m) std::memcpy(r.world_to_ndc, m->data(), sizeof(r.world_to_ndc));
  return r;
}

// A loaded asset with its JSON, so that objects can be looked up by name.
struct model {
  fs::path file;
  json doc;
  scene world;
};

model load(const fs::path& file) { return {file, gltf_json(file), load_gltf(file.string())}; }

// World bounds of what the glTF node named `name` places itself (not its children); nodes without a
// name are matched by their mesh's name.
bounds3 node_bounds(const model& m, const std::string& name) {
  int node = -1;
  const json& nodes = m.doc["nodes"];
  for (size_t i = 0; i < nodes.size() && node < 0; ++i)
    if (nodes[i].value("name", "") == name) node = int(i);
  for (size_t i = 0; i < nodes.size() && node < 0; ++i)
    if (nodes[i].contains("mesh") && m.doc["meshes"][nodes[i]["mesh"].get<int>()].value("name", "") == name)
      node = int(i);
  bounds3 b;
  for (const instance& inst : m.world.instances)
    if (int(inst.node) == node && inst.kind == shape_kind::mesh)
      b.extend(transform_bounds(inst.world_from_object, m.world.meshes[inst.shape].bounds));
  EXPECT_FALSE(b.empty()) << "no geometry for node '" << name << "' in " << m.file;
  return b;
}

// The pixel rectangle covering the projected world bounds, clipped to the image.
rect screen_rect(const rendering& r, const bounds3& b) {
  double x0 = inf, y0 = inf, x1 = -inf, y1 = -inf;
  for (int i = 0; i < 8; ++i) {
    glm::dvec2 p = r.project(dvec3((i & 1) ? b.upper.x : b.lower.x, (i & 2) ? b.upper.y : b.lower.y,
                                   (i & 4) ? b.upper.z : b.lower.z));
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  return {std::max(0, int(std::ceil(x0))), std::max(0, int(std::ceil(y0))),
          std::min(r.width, int(std::floor(x1))), std::min(r.height, int(std::floor(y1)))};
}

rect node_rect(const model& m, const rendering& r, const std::string& name) {
  return screen_rect(r, node_bounds(m, name));
}

size_t count(const rendering& r, const rect& area, const std::function<bool(const rgb&)>& test) {
  size_t n = 0;
  for (int y = area.y0; y < area.y1; ++y)
    for (int x = area.x0; x < area.x1; ++x) n += test(r.color(x, y));
  return n;
}

double share(const rendering& r, const rect& area, const std::function<bool(const rgb&)>& test) {
  return double(count(r, area, test)) / std::max(1, area.width() * area.height());
}

rgb mean(const rendering& r, const rect& area) {
  rgb sum;
  for (int y = area.y0; y < area.y1; ++y)
    for (int x = area.x0; x < area.x1; ++x) {
      rgb c = r.color(x, y);
      sum.r += c.r, sum.g += c.g, sum.b += c.b;
    }
  float n = float(std::max(1, area.width() * area.height()));
  return {sum.r / n, sum.g / n, sum.b / n};
}

// Colour classes: one channel clearly above the other two.
bool greenish(const rgb& c) { return c.g > 0.05f && c.g > 2.0f * c.r && c.g > 2.0f * c.b; }
bool reddish(const rgb& c) { return c.r > 0.05f && c.r > 2.0f * c.g && c.r > 2.0f * c.b; }
bool blueish(const rgb& c) { return c.b > 0.05f && c.b > 2.0f * c.r && c.b > 2.0f * c.g; }

// Problems found by a check; empty when the render looks as the README says it should.
using problems = std::vector<std::string>;

std::string describe(const problems& p) {
  std::string text;
  for (const std::string& line : p) text += "\n  " + line;
  return text;
}

// README: the TopLeft quad shows the upper-left part of the texture (UV 0..0.4), and so on; each
// part has its label and a checkered corner mark, so the dark pixels of each quad lie in its outer
// corner. A flipped U or V moves them to another corner.
TEST(asset_pixels, texture_coordinate_test_puts_each_texture_corner_on_its_quad) {
  SKIP_WITHOUT_ASSETS();
  model m = load(asset("TextureCoordinateTest/glTF-Binary/TextureCoordinateTest.glb"));
  rendering r = render(m.file, "texcoord", 512, 512);
  struct quad {
    const char* node;
    int corner;  // 0 top left, 1 top right, 2 bottom left, 3 bottom right
    std::function<bool(const rgb&)> colour;
  };
  const quad quads[] = {
      {"TopLeftObj", 0, [](const rgb& c) { return c.r > 3 * c.b && c.g > 3 * c.b && c.g > 0.6f * c.r; }},
      {"TopRightObj", 1, [](const rgb& c) { return c.r > 3 * c.g && c.g > 3 * c.b; }},
      {"BottomLeftObj", 2, blueish},
      {"BottomRightObj", 3, greenish}};
  for (const quad& q : quads) {
    SCOPED_TRACE(q.node);
    rect area = node_rect(m, r, q.node).part(0.02, 0.02, 0.98, 0.98);
    EXPECT_GT(share(r, area, q.colour), 0.8) << area;
    float base = mean(r, area).luma();
    size_t dark[4];
    for (int k = 0; k < 4; ++k) {
      rect quarter = area.part(0.5 * (k % 2), 0.5 * (k / 2), 0.5 * (k % 2) + 0.5, 0.5 * (k / 2) + 0.5);
      dark[k] = count(r, quarter, [&](const rgb& c) { return c.luma() < 0.3f * base; });
    }
    for (int k = 0; k < 4; ++k) {
      if (k == q.corner) continue;
      EXPECT_GT(dark[q.corner], 3 * dark[k]) << "dark pixels in quarter " << k << " of " << area;
    }
  }
}

// README: offsets (0.5,0), (0,0.5), (0.5,0.5) on UV 0..0.5 show the green, blue and cyan parts of
// UV.png; yellow (its unshifted quarter) means no offset.
TEST(asset_pixels, texture_transform_test_offsets_pick_the_right_quarter) {
  SKIP_WITHOUT_ASSETS();
  model m = load(asset("TextureTransformTest/glTF/TextureTransformTest.gltf"));
  rendering r = render(m.file, "transform_offset", 256, 256);
  auto cyan = [](const rgb& c) {
    return c.g > 0.05f && c.g > 2 * c.r && c.b > 2 * c.r && c.b > 0.5f * c.g && c.g > 0.5f * c.b;
  };
  auto yellow = [](const rgb& c) { return c.r > 0.05f && c.r > 2 * c.b && c.g > 2 * c.b; };
  const std::pair<const char*, std::function<bool(const rgb&)>> quads[] = {
      {"Offset U", greenish}, {"Offset V", blueish}, {"Offset UV", cyan}};
  for (const auto& [node, colour] : quads) {
    rect area = node_rect(m, r, node).part(0.1, 0.1, 0.9, 0.9);
    EXPECT_GT(share(r, area, colour), 0.5) << node << " " << area;
    EXPECT_LT(share(r, area, yellow), 0.02) << node << " " << area;
  }
}

// The arrow of a quad: its dark pixels outside the markers.
struct arrow {
  std::vector<glm::dvec2> pixels;
  // How close the arrow comes to a point.
  double distance(const glm::dvec2& p) const {
    double d = inf;
    for (const glm::dvec2& q : pixels) d = std::min(d, glm::length(q - p));
    return d;
  }
  // Angle in degrees between the arrow's principal axis and the line from its centroid to p.
  double axis_angle_to(const glm::dvec2& p) const {
    glm::dvec2 c(0.0);
    for (const glm::dvec2& q : pixels) c += q / double(pixels.size());
    double xx = 0, yy = 0, xy = 0;
    for (const glm::dvec2& q : pixels)
      xx += (q.x - c.x) * (q.x - c.x), yy += (q.y - c.y) * (q.y - c.y), xy += (q.x - c.x) * (q.y - c.y);
    double axis = 0.5 * std::atan2(2 * xy, xx - yy);
    glm::dvec2 to = glm::normalize(p - c);
    return std::acos(std::min(1.0, std::abs(to.x * std::cos(axis) + to.y * std::sin(axis)))) * 180.0 / pi;
  }
};

glm::dvec2 centre(const rect& k) { return {0.5 * (k.x0 + k.x1), 0.5 * (k.y0 + k.y1)}; }

arrow find_arrow(const rendering& r, const rect& quad, const std::vector<rect>& markers) {
  arrow a;
  for (int y = quad.y0; y < quad.y1; ++y)
    for (int x = quad.x0; x < quad.x1; ++x) {
      bool in_marker = false;
      for (const rect& k : markers) in_marker |= k.part(-0.2, -0.2, 1.2, 1.2).contains(x, y);
      if (!in_marker && r.color(x, y).luma() < 0.03f) a.pixels.push_back({x + 0.5, y + 0.5});
    }
  EXPECT_GT(a.pixels.size(), size_t(0.01 * quad.width() * quad.height())) << "no arrow in " << quad;
  return a;
}

// README: the arrows of the rotation, scale and combined quads point at the green "Correct"
// markers; the yellow "Not Supported" marker is where an arrow points without the transform, the
// red "Error" one where a rotation the wrong way points. So the arrow's axis must aim at the
// Correct marker, its tip end near it, and stay clear of the other markers.
problems arrow_problems(const fs::path& file, const std::string& name) {
  model m = load(file);
  rendering r = render(file, name, 768, 768);
  const std::pair<const char*, std::vector<std::string>> quads[] = {
      {"Rotation", {"Rotation - Correct", "Rotation - Not Supported", "Rotation - Error"}},
      {"Scale", {"Scale - Correct", "Scale - Not Supported"}},
      {"All", {"All - Correct"}}};
  problems found;
  for (const auto& [quad, marker_nodes] : quads) {
    rect area = node_rect(m, r, quad);
    std::vector<rect> markers;
    for (const std::string& n : marker_nodes) markers.push_back(node_rect(m, r, n));
    arrow a = find_arrow(r, area, markers);
    if (a.pixels.empty()) continue;
    double correct = a.distance(centre(markers[0])), angle = a.axis_angle_to(centre(markers[0]));
    if (!(correct < 0.16 * area.width()))
      found.push_back(std::string(quad) + ": arrow ends " + format_number(correct) +
                      " px from the Correct marker");
    if (!(angle < 10.0))
      found.push_back(std::string(quad) + ": arrow axis " + format_number(angle) +
                      " degrees off the Correct marker");
    for (size_t i = 1; i < markers.size(); ++i) {
      double other = a.distance(centre(markers[i]));
      if (!(other > 0.3 * area.width() && correct < 0.6 * other))
        found.push_back(std::string(quad) + ": arrow comes " + format_number(other) + " px near " +
                        marker_nodes[i] + " (Correct: " + format_number(correct) + ")");
    }
  }
  return found;
}

TEST(asset_pixels, texture_transform_test_arrows_point_at_the_correct_markers) {
  SKIP_WITHOUT_ASSETS();
  problems p =
      arrow_problems(asset("TextureTransformTest/glTF/TextureTransformTest.gltf"), "transform_arrows");
  EXPECT_TRUE(p.empty()) << describe(p);
}

// The check above tells a missing transform apart: without KHR_texture_transform on the three
// arrow materials each quad fails it.
TEST(asset_pixels, texture_transform_test_arrow_check_fails_without_the_transform) {
  SKIP_WITHOUT_ASSETS();
  fs::path source = asset("TextureTransformTest/glTF");
  fs::path copy = testing::scratch_folder("transform_removed");
  for (const auto& entry : fs::directory_iterator(source))
    fs::copy(entry.path(), copy / entry.path().filename());
  json doc = gltf_json(source / "TextureTransformTest.gltf");
  for (auto& mat : doc["materials"])
    if (mat["name"] == "Rotation" || mat["name"] == "Scale" || mat["name"] == "All")
      mat["pbrMetallicRoughness"]["baseColorTexture"].erase("extensions");
  std::ofstream(copy / "TextureTransformTest.gltf") << doc.dump();
  problems p = arrow_problems(copy / "TextureTransformTest.gltf", "transform_removed_render");
  for (const char* quad : {"Rotation", "Scale", "All"})
    EXPECT_TRUE(std::any_of(p.begin(), p.end(), [&](const std::string& s) { return s.rfind(quad, 0) == 0; }))
        << quad << describe(p);
}

// README: the top row's checks are multiplied by red, green and blue vertex colours; without
// COLOR_0 they show X marks in the other two channels. They must match the "Sample pass" row.
problems vertex_color_problems(const fs::path& file, const std::string& name) {
  model m = load(file);
  rendering r = render(file, name, 512, 512);
  rect panel = node_rect(m, r, "VertexColorTest");
  problems found;
  for (int column = 0; column < 3; ++column) {
    double x0 = 0.13 + 0.275 * column, x1 = x0 + 0.19;
    rgb test = mean(r, panel.part(x0, 0.23, x1, 0.42)), sample = mean(r, panel.part(x0, 0.67, x1, 0.86));
    const float t[3] = {test.r, test.g, test.b}, s[3] = {sample.r, sample.g, sample.b};
    if (!(s[column] > 0.05f)) found.push_back("sample " + std::to_string(column) + " has no check");
    // The check's own channel within 10%; the two channels the vertex colour zeroes within 3%.
    for (int c = 0; c < 3; ++c)
      if (!(std::abs(t[c] - s[c]) <= (c == column ? 0.1f : 0.03f) * s[column]))
        found.push_back("cell " + std::to_string(column) + " channel " + std::to_string(c) + ": test " +
                        format_number(t[c]) + ", sample " + format_number(s[c]));
  }
  return found;
}

TEST(asset_pixels, vertex_color_test_rows_match) {
  SKIP_WITHOUT_ASSETS();
  problems p =
      vertex_color_problems(asset("VertexColorTest/glTF-Binary/VertexColorTest.glb"), "vertex_color");
  EXPECT_TRUE(p.empty()) << describe(p);
}

TEST(asset_pixels, vertex_color_test_check_fails_without_color_0) {
  SKIP_WITHOUT_ASSETS();
  fs::path file = asset("VertexColorTest/glTF-Binary/VertexColorTest.glb");
  json doc = gltf_json(file);
  for (auto& mesh : doc["meshes"])
    for (auto& prim : mesh["primitives"]) prim["attributes"].erase("COLOR_0");
  fs::path copy = fs::path(testing::scratch_folder("vertex_color_removed")) / "VertexColorTest.glb";
  write_glb(file, doc, copy);
  problems p = vertex_color_problems(copy, "vertex_color_removed_render");
  EXPECT_GE(p.size(), 3u) << describe(p);
}

// README: each Test cell looks like its Sample-pass cell: green checks, solid green for the clamps;
// failures show red X marks or solid red. Each row's mesh holds both cells, Test on the left.
problems texture_settings_problems(const model& m, const rendering& r, const std::string& row) {
  rect area = node_rect(m, r, row);
  rect test = area.part(0.0, 0.0, 0.5, 1.0), sample = area.part(0.5, 0.0, 1.0, 1.0);
  double test_green = share(r, test, greenish), sample_green = share(r, sample, greenish);
  problems found;
  if (!(sample_green > 0.05))
    found.push_back(row + ": no green in the sample cell " + format_number(sample_green));
  if (!(std::abs(test_green - sample_green) < 0.2 * sample_green))
    found.push_back(row + ": green share of the test cell " + format_number(test_green) + ", of the sample " +
                    format_number(sample_green));
  if (!(share(r, test, reddish) < 0.005))
    found.push_back(row + ": red in the test cell " + format_number(share(r, test, reddish)));
  return found;
}

TEST(asset_pixels, texture_settings_test_sampler_cells_match_their_samples) {
  SKIP_WITHOUT_ASSETS();
  model m = load(asset("TextureSettingsTest/glTF-Binary/TextureSettingsTest.glb"));
  rendering r = render(m.file, "texture_settings", 512, 512);
  for (const char* row : {"DoubleSidedMesh", "TextureClampMeshS", "TextureClampMeshT", "TextureRepeatMeshS",
                          "TextureRepeatMeshT", "TextureMirrorMeshS", "TextureMirrorMeshT"}) {
    problems p = texture_settings_problems(m, r, row);
    EXPECT_TRUE(p.empty()) << describe(p);
  }
  // The clamp tests are solid green boxes (most of each half), the others checks on white.
  for (const char* row : {"TextureClampMeshS", "TextureClampMeshT"})
    EXPECT_GT(share(r, node_rect(m, r, row).part(0.0, 0.0, 0.5, 1.0), greenish), 0.4) << row;
}

// The single-sided row: a polygon facing away from the camera, in front of a check, must be culled
// so that the check shows as in the sample cell: lit by the default headlight, whose shadow rays
// would otherwise meet the culled polygon on their way back to the camera.
TEST(asset_pixels, texture_settings_test_single_sided_polygon_hides_nothing) {
  SKIP_WITHOUT_ASSETS();
  model m = load(asset("TextureSettingsTest/glTF-Binary/TextureSettingsTest.glb"));
  rendering r = render(m.file, "texture_settings_single", 512, 512);
  problems p = texture_settings_problems(m, r, "SingleSidedMesh");
  EXPECT_TRUE(p.empty()) << describe(p);
}

// Depth behind the culled polygon is the camera's distance to the check, as for the double-sided
// row's check next to it, not the distance from the culled polygon.
TEST(asset_pixels, texture_settings_test_depth_behind_a_culled_polygon_is_from_the_camera) {
  SKIP_WITHOUT_ASSETS();
  model m = load(asset("TextureSettingsTest/glTF-Binary/TextureSettingsTest.glb"));
  rendering r = render(m.file, "texture_settings_depth", 512, 512);
  rect single = node_rect(m, r, "SingleSidedMesh").part(0.2, 0.4, 0.3, 0.6);
  rect twin = node_rect(m, r, "DoubleSidedMesh").part(0.2, 0.4, 0.3, 0.6);
  float depth = r.depth(single.x0, single.y0), twin_depth = r.depth(twin.x0, twin.y0);
  EXPECT_NEAR(depth, twin_depth, 0.1f * twin_depth);
}

// Straight-on view of the five alpha test boxes.
rendering render_alpha_modes(const model& m) {
  return render(m.file, "alpha_modes", 768, 384,
                {"--look-from", "0,1,12", "--look-at", "0,1,0", "--fov", "20"});
}

// README: OPAQUE ignores the texture's alpha and BLEND blends it; either mistake turns the green
// check beside the label into a red X. DecalBlend is the check beside BLEND; the one beside OPAQUE
// is the same distance left of its box.
TEST(asset_pixels, alpha_blend_mode_test_shows_checks_beside_opaque_and_blend) {
  SKIP_WITHOUT_ASSETS();
  model m = load(asset("AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb"));
  rendering r = render_alpha_modes(m);
  bounds3 blend = node_bounds(m, "DecalBlend");
  dvec3 shift = node_bounds(m, "TestOpaque").center() - node_bounds(m, "TestBlend").center();
  bounds3 opaque{blend.lower + dvec3(shift.x, 0, 0), blend.upper + dvec3(shift.x, 0, 0)};
  for (const auto& [label, box] : {std::pair{"OPAQUE", opaque}, std::pair{"BLEND", blend}}) {
    rect area = screen_rect(r, box);
    EXPECT_GT(share(r, area, greenish), 0.1) << label << " " << area;
    EXPECT_LT(share(r, area, reddish), 0.01) << label << " " << area;
  }
}

// Rows of a box's centre column, below the top edge of its opaque frame, where the ray passes the
// cut-away ramp to the wall behind (until it hits the box again: depth within 1% of the box's).
int cut_away_rows(const model& m, const rendering& r, const std::string& node) {
  rect area = node_rect(m, r, node);
  int x = (area.x0 + area.x1) / 2;
  double plane = glm::length(dvec3(0, 1, 12) - node_bounds(m, node).center());
  auto on_box = [&](int y) { return std::abs(r.depth(x, y) - plane) < 0.01 * plane; };
  int y = area.y0;
  while (y < area.y1 && !on_box(y)) ++y;  // transparent margin above the frame
  while (y < area.y1 && on_box(y)) ++y;   // the frame's opaque top edge
  int ramp_top = y;
  while (y < area.y1 && !on_box(y)) ++y;
  return y - ramp_top;
}

// README: MASK boxes hold a linear alpha ramp from 0 at the top to 1 at the bottom, cut at 0.25,
// the default 0.5 and 0.75. So the cut-away heights are evenly spaced: a cutoff ignored (all at
// 0.5) or a wrong default breaks that.
TEST(asset_pixels, alpha_blend_mode_test_mask_cuts_the_ramp_at_each_cutoff) {
  SKIP_WITHOUT_ASSETS();
  model m = load(asset("AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb"));
  rendering r = render_alpha_modes(m);
  double height = node_rect(m, r, "TestCutoff25").height();
  double at25 = cut_away_rows(m, r, "TestCutoff25"), at50 = cut_away_rows(m, r, "TestCutoffDefault"),
         at75 = cut_away_rows(m, r, "TestCutoff75");
  // The ramp covers most of the box, so half of it is well over a third of the box's height.
  EXPECT_GT(at75 - at25, 0.35 * height) << at25 << " " << at50 << " " << at75;
  EXPECT_NEAR(at50, 0.5 * (at25 + at75), 0.03 * height) << at25 << " " << at50 << " " << at75;
  EXPECT_GT(at25, 0.0);
}

// MultiUVTest's emissive texture uses TEXCOORD_1, which lays the glTF logo (green) on each face;
// through TEXCOORD_0 the same texture shows white "Multiple UVs not supported" text instead.
TEST(asset_pixels, multi_uv_test_emissive_uses_the_second_uv_set) {
  SKIP_WITHOUT_ASSETS();
  model m = load(asset("MultiUVTest/glTF-Binary/MultiUVTest.glb"));
  rendering r = render(m.file, "multi_uv", 384, 216);
  json doc = m.doc;
  doc["materials"][0]["emissiveTexture"]["texCoord"] = 0;
  fs::path copy = fs::path(testing::scratch_folder("multi_uv_texcoord0")) / "MultiUVTest.glb";
  write_glb(m.file, doc, copy);
  rendering first_set = render(copy, "multi_uv_texcoord0_render", 384, 216);
  rect cube = node_rect(m, r, "Cube");
  auto logo = [](const rgb& c) { return c.g > 0.5f && c.g > 1.5f * c.b && c.g > 1.3f * c.r; };
  auto text = [](const rgb& c) { return c.r > 0.7f && c.g > 0.7f && c.b > 0.7f; };
  EXPECT_GT(share(r, cube, logo), 0.03);
  EXPECT_LT(share(r, cube, text), 0.2 * share(first_set, cube, text));
  EXPECT_GT(share(first_set, cube, text), 0.01);
  EXPECT_LT(share(first_set, cube, logo), 0.2 * share(r, cube, logo));
}

// Luminance on an n×n grid over a world-space square in the plane z, as the camera sees it.
std::vector<double> luma_grid(const rendering& r, const bounds3& square, int n, double z) {
  std::vector<double> values;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      dvec3 p(square.lower.x + (i + 0.5) / n * (square.upper.x - square.lower.x),
              square.upper.y - (j + 0.5) / n * (square.upper.y - square.lower.y), z);
      glm::dvec2 px = r.project(p);
      int x = std::clamp(int(px.x), 0, r.width - 1), y = std::clamp(int(px.y), 0, r.height - 1);
      values.push_back(r.color(x, y).luma());
    }
  return values;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (size_t i = 0; i < a.size(); ++i) ma += a[i] / a.size(), mb += b[i] / b.size();
  double ab = 0, aa = 0, bb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb), aa += (a[i] - ma) * (a[i] - ma), bb += (b[i] - mb) * (b[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

// The part of a grid's brightness that changes sign through its centre (v(p) - v(-p)): the side a
// bump is lit from, without the falloff toward its rim that any orientation shares.
std::vector<double> lit_side(const std::vector<double>& v, int n) {
  std::vector<double> out(v.size());
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) out[j * n + i] = v[j * n + i] - v[(n - 1 - j) * n + (n - 1 - i)];
  return out;
}

// The grid upside down: what a flipped green channel would do to a normal-mapped cell's shading.
std::vector<double> flip_rows(const std::vector<double>& v, int n) {
  std::vector<double> out(v.size());
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) out[j * n + i] = v[(n - 1 - j) * n + i];
  return out;
}

// Adds one directional light to a glTF document, shining along `direction`.
void add_directional_light(json& doc, const dvec3& direction) {
  doc["extensionsUsed"].push_back("KHR_lights_punctual");
  doc["extensions"]["KHR_lights_punctual"]["lights"] =
      json::array({{{"type", "directional"}, {"intensity", 3.0}}});
  // The light shines along its node's -Z: the node's basis has z = -direction.
  dvec3 z = -glm::normalize(direction), x = glm::normalize(glm::cross(dvec3(0, 1, 0), z)),
        y = glm::cross(z, x);
  doc["nodes"].push_back({{"name", "test light"},
                          {"matrix", {x.x, x.y, x.z, 0, y.x, y.y, y.z, 0, z.x, z.y, z.z, 0, 0, 0, 0, 1}},
                          {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  doc["scenes"][doc.value("scene", 0)]["nodes"].push_back(doc["nodes"].size() - 1);
}

// Replaces the .glb's normal map by a copy with its green channel inverted (the left-handed
// normal map mistake the README shows), written as a PNG into `folder`.
void flip_normal_map_green(const model& m, json& doc, const fs::path& folder) {
  int image = doc["textures"][doc["materials"][0]["normalTexture"]["index"].get<int>()]["source"];
  const json& view = doc["bufferViews"][doc["images"][image]["bufferView"].get<int>()];
  std::string bytes = read_bytes(m.file);
  uint32_t json_length = 0;
  std::memcpy(&json_length, bytes.data() + 12, 4);
  size_t bin = 20 + json_length + 8;  // the binary chunk's data, after its length and type
  fs::path original = folder / "normal.png", flipped = folder / "normal_flipped.png";
  std::ofstream(original, std::ios::binary)
      << bytes.substr(bin + view.value("byteOffset", size_t(0)), view["byteLength"].get<size_t>());
  auto in = OIIO::ImageInput::open(original.string());
  ASSERT_TRUE(in);
  OIIO::ImageSpec spec = in->spec();
  std::vector<uint8_t> texels(size_t(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, texels.data()));
  for (size_t i = 1; i < texels.size(); i += spec.nchannels) texels[i] = uint8_t(255 - texels[i]);
  auto out = OIIO::ImageOutput::create(flipped.string());
  ASSERT_TRUE(out && out->open(flipped.string(), spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, texels.data()));
  out->close();
  doc["images"][image] = {{"uri", flipped.filename().string()}};
}

// For each normal-mapped bump, the correlation of its lit side with its real-geometry twin's, and
// with the twin's upside down: NormalTangentTest lit from above (by an added light), seen straight
// on from far away so that the bumps line up with their cells. The third pair of each row, a
// mirror, has nothing to reflect here and is left out.
std::vector<std::pair<double, double>> normal_tangent_correlations(bool flip_green, const std::string& name) {
  model m = load(asset("NormalTangentTest/glTF-Binary/NormalTangentTest.glb"));
  json doc = m.doc;
  fs::path folder = testing::scratch_folder(name);
  add_directional_light(doc, dvec3(0, -1, -2));
  if (flip_green) flip_normal_map_green(m, doc, folder);
  write_glb(m.file, doc, folder / "NormalTangentTest.glb");
  rendering r = render(folder / "NormalTangentTest.glb", name + "_render", 512, 512,
                       {"--look-from", "0,-0.125,40", "--look-at", "0,-0.125,0", "--fov", "3.5"});
  bounds3 panel = node_bounds(m, m.doc["meshes"][0]["name"]);
  // Cell columns and rows as fractions of the panel (x from the left, y from the top).
  const double columns[4][2] = {{0.0, 0.136}, {0.147, 0.283}, {0.36, 0.496}, {0.505, 0.64}};
  const double rows[5][2] = {{0.0, 0.14}, {0.186, 0.326}, {0.372, 0.512}, {0.558, 0.698}, {0.744, 0.884}};
  // The middle 60% of a cell: the bump, clear of the shadow the real one casts.
  auto bump = [&](int column, int row) {
    dvec3 size = panel.diagonal();
    auto inset = [](const double* range, double f) { return range[0] + f * (range[1] - range[0]); };
    bounds3 b;
    b.extend(dvec3(panel.lower.x + inset(columns[column], 0.2) * size.x,
                   panel.upper.y - inset(rows[row], 0.8) * size.y, 0.0));
    b.extend(dvec3(panel.lower.x + inset(columns[column], 0.8) * size.x,
                   panel.upper.y - inset(rows[row], 0.2) * size.y, 0.0));
    return b;
  };
  const int n = 16;
  std::vector<std::pair<double, double>> result;
  for (int pair = 0; pair < 2; ++pair)
    for (int row = 0; row < 5; ++row) {
      std::vector<double> real = luma_grid(r, bump(2 * pair, row), n, 0.0),
                          mapped = luma_grid(r, bump(2 * pair + 1, row), n, 0.0);
      result.push_back({correlation(lit_side(real, n), lit_side(mapped, n)),
                        correlation(lit_side(flip_rows(real, n), n), lit_side(mapped, n))});
    }
  return result;
}

// Least correlation of a normal-mapped bump's lit side with its twin's. Measured: 0.89..0.98 as
// kiln renders the asset; at most 0.51 with the normal map's green channel inverted (each row
// turns its UVs by another angle, so the inversion turns the lit side by 60 degrees or more).
constexpr double normal_map_agreement = 0.8;

// README (NormalTangentTest supplies no tangents, so kiln generates them): each pair has real
// geometry on the left and a normal-mapped flat quad on the right, and both must shade alike.
TEST(asset_pixels, normal_tangent_test_normal_maps_shade_like_their_geometry) {
  SKIP_WITHOUT_ASSETS();
  auto correlations = normal_tangent_correlations(false, "normal_tangent");
  for (size_t i = 0; i < correlations.size(); ++i) {
    EXPECT_GT(correlations[i].first, normal_map_agreement) << "cell pair " << i;
    // The light is far enough off axis that upside down they differ, as a flipped Y would.
    EXPECT_LT(correlations[i].second, 0.0) << "cell pair " << i;
  }
}

// The check above catches the README's failure: with the normal map's green channel inverted no
// bump follows its twin any more.
TEST(asset_pixels, normal_tangent_test_check_fails_with_green_flipped) {
  SKIP_WITHOUT_ASSETS();
  auto correlations = normal_tangent_correlations(true, "normal_tangent_flipped");
  for (size_t i = 0; i < correlations.size(); ++i) {
    EXPECT_LT(correlations[i].first, normal_map_agreement) << "cell pair " << i;
  }
}

}  // namespace
}  // namespace kiln
