// Render layers recombined as a compositor recombines them, on a scene with overlapping edges, glass
// and a BLEND surface, read back with OpenEXR's own deep reader and merged here independently:
// - deep layers (--others invisible, the default with --deep) merged by depth and flattened give
//   the full render's alpha on every pixel and its colour on interior pixels; a layer has no hole
//   where the other's objects stand, and its ids and Cryptomatte name its own objects only;
// - a DeepHoldout of one deep layer by the other (Nuke's: each sample times the holdout's
//   transmittance in front of it) is the flat matte render of that layer;
// - flat layers (--others matte, the default without --deep) add (`plus`) to the full render on
//   every pixel, edges included, and `over` does not;
// - a matte writes nothing to the layer's utility passes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "support/channel_exr.h"
#include "support/deep_exr.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

using testing::channel_exr;
using testing::deep_file;

constexpr int size = 48;
constexpr float veil_alpha = 0.6f;
const std::string objects = "obj_*";
const char* const rgba[4] = {"R", "G", "B", "A"};
// Node indices, in the order write_scene adds them: the room first, then the objects.
const std::set<int> room_nodes = {0, 1}, object_nodes = {2, 3, 4};

// A room (a lit back wall filling the view and a grey slab on it) and three objects in front of it
// that overlap one another's edges: a red opaque triangle, a glass pane over part of it and a
// BLEND veil (alpha 0.6) over part of both. A point light casts the objects' shadows on the wall.
std::string write_scene(const std::string& path) {
  testing::gltf_builder b;
  auto diffuse = [&](const char* name, std::array<float, 4> colour) {
    nlohmann::json m = {{"name", name},
                        {"pbrMetallicRoughness", {{"baseColorFactor", colour}, {"metallicFactor", 0.0}}}};
    if (colour[3] < 1.0f) m["alphaMode"] = "BLEND";
    return b.add_material(m);
  };
  const int wall = diffuse("wall", {0.8f, 0.8f, 0.7f, 1});
  const int slab = diffuse("slab", {0.3f, 0.4f, 0.5f, 1});
  const int red = diffuse("red", {1, 0.1f, 0.1f, 1});
  const int veil = diffuse("veil", {0.2f, 0.9f, 0.3f, veil_alpha});
  const int glass = b.add_material(
      {{"name", "glass"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.0}}},
       {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}});
  b.doc["extensionsUsed"].push_back("KHR_materials_transmission");
  const std::vector<std::array<float, 3>> facing = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  auto quad = [&](const char* name, float x0, float y0, float x1, float y1, float z, int material) {
    b.add_node({{"name", name},
                {"mesh", b.add_mesh({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, {0, 1, 2, 0, 2, 3},
                                    material, facing)}});
  };
  quad("room_wall", -4, -4, 4, 4, 0, wall);
  quad("room_slab", 0.2f, -1.2f, 1.4f, 0.9f, 0.05f, slab);
  b.add_node({{"name", "obj_triangle"},
              {"mesh", b.add_mesh({{-0.9f, -0.7f, 0.5f}, {0.6f, -0.5f, 0.5f}, {-0.3f, 0.8f, 0.5f}}, {0, 1, 2},
                                  red, {facing[0], facing[1], facing[2]})}});
  quad("obj_glass", -0.2f, -0.9f, 0.7f, 0.2f, 0.9f, glass);
  quad("obj_veil", -1.1f, 0.0f, 0.3f, 0.7f, 1.3f, veil);
  b.add_lamp_and_camera({1.0, 0.8, 2.5}, 12.0, {0, 0, 4}, 0.8);
  b.write(path);
  return path;
}

channel_exr render(const std::string& scene, const std::string& out, std::vector<std::string> extra) {
  extra.insert(extra.end(), {"--aovs", "beauty,Z,N,P,uv,id,albedo,crypto_object", "--lighting", "file"});
  return testing::render_float_exr(scene, out, size, size, extra);
}

// Front to back over the samples of both files (sorted by Z): C += T·c, T *= 1 − a.
std::array<float, 4> merged(const deep_file& a, const deep_file& b, size_t p) {
  std::vector<std::pair<float, std::array<float, 4>>> samples;
  for (const deep_file* f : {&a, &b})
    for (unsigned int k = 0; k < f->counts[p]; ++k)
      samples.push_back(
          {f->at(p, k, "Z"), {f->at(p, k, "R"), f->at(p, k, "G"), f->at(p, k, "B"), f->at(p, k, "A")}});
  std::stable_sort(samples.begin(), samples.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::array<float, 4> out{0, 0, 0, 0};
  float transmittance = 1.0f;
  for (const auto& s : samples) {
    for (int c = 0; c < 4; ++c) out[size_t(c)] += transmittance * s.second[size_t(c)];
    transmittance *= 1.0f - s.second[3];
  }
  return out;
}

// Nuke's DeepHoldout of src by holdout, flattened: each sample of src times the transmittance of
// the holdout's samples in front of it, then src flattened front to back.
std::array<float, 4> held_out(const deep_file& src, const deep_file& holdout, size_t p) {
  std::array<float, 4> out{0, 0, 0, 0};
  float transmittance = 1.0f;
  for (unsigned int k = 0; k < src.counts[p]; ++k) {
    const float z = src.at(p, k, "Z");
    float through_holdout = 1.0f;
    for (unsigned int h = 0; h < holdout.counts[p]; ++h)
      if (holdout.at(p, h, "Z") < z) through_holdout *= 1.0f - holdout.at(p, h, "A");
    for (int c = 0; c < 4; ++c) out[size_t(c)] += transmittance * through_holdout * src.at(p, k, rgba[c]);
    transmittance *= 1.0f - src.at(p, k, "A");
  }
  return out;
}

// Whether every holdout sample of pixel p lies in front of every sample of src: there a DeepHoldout
// cuts exactly what the matte cuts, edges included.
bool holdout_in_front(const deep_file& src, const deep_file& holdout, size_t p) {
  float back = 0.0f, front = INFINITY;
  for (unsigned int h = 0; h < holdout.counts[p]; ++h) back = std::max(back, holdout.at(p, h, "ZBack"));
  for (unsigned int k = 0; k < src.counts[p]; ++k) front = std::min(front, src.at(p, k, "Z"));
  return back < front;
}

// Interior pixels: the objects' layer covers the pixel and its eight neighbours alike, with alpha 0,
// the veil's alone or 1. Elsewhere a pixel's samples see different objects, and a merge by depth
// can differ from the full render by how the layer behind varies inside the pixel.
std::vector<bool> interior_pixels(const channel_exr& object_layer) {
  auto whole = [&](float a) {
    return std::abs(a) < 1e-6f || std::abs(a - veil_alpha) < 1e-6f || std::abs(a - 1.0f) < 1e-6f;
  };
  std::vector<bool> out(size_t(size) * size, false);
  for (int y = 1; y + 1 < size; ++y)
    for (int x = 1; x + 1 < size; ++x) {
      const float a = object_layer.at(size_t(y * size + x), "A");
      bool same = whole(a);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          same = same && object_layer.at(size_t((y + dy) * size + x + dx), "A") == a;
      out[size_t(y * size + x)] = same;
    }
  return out;
}

float relative(float got, float want) { return std::abs(got - want) / std::max(1.0f, std::abs(want)); }

// The id.object values of a flat layer (-1: nothing).
std::set<int> object_ids(const channel_exr& layer) {
  std::set<int> out;
  for (size_t p = 0; p < layer.count(); ++p) out.insert(int(layer.at(p, "id.object")));
  return out;
}

// The manifest of a file's CryptoObject layer (its key found by name, as Nuke's decoder finds it).
std::string crypto_object_manifest(const channel_exr& layer) {
  for (const OIIO::ParamValue& attribute : layer.spec.extra_attribs) {
    const std::string name = attribute.name().string();
    if (name.size() > 5 && name.compare(name.size() - 5, 5, "/name") == 0 &&
        layer.spec.get_string_attribute(name) == "CryptoObject")
      return layer.spec.get_string_attribute(name.substr(0, name.size() - 5) + "/manifest");
  }
  ADD_FAILURE() << "no CryptoObject layer";
  return "";
}

struct layers {
  channel_exr full, objects, room;
  deep_file objects_deep, room_deep;
};

layers render_deep_layers(const std::string& dir, const std::string& spp, const std::string& others) {
  const std::string scene = write_scene(dir + "/scene.gltf");
  std::vector<std::string> common = {"--spp", spp};
  if (!others.empty()) common.insert(common.end(), {"--others", others});
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.end(), common.begin(), common.end());
    return extra;
  };
  layers out{render(scene, dir + "/full.exr", {"--spp", spp}),
             render(scene, dir + "/objects.exr", with({"--only", objects, "--deep"})),
             render(scene, dir + "/room.exr", with({"--holdout", objects, "--deep"})),
             {},
             {}};
  out.objects_deep = testing::read_deep(dir + "/objects.deep.exr");
  out.room_deep = testing::read_deep(dir + "/room.deep.exr");
  return out;
}

TEST(render_layers_cli, deep_layers_of_disjoint_objects_merge_into_the_full_render) {
  for (const std::string spp : {"1", "16"}) {
    const std::string dir = testing::scratch_folder("render_layers_deep_" + spp);
    const layers l = render_deep_layers(dir, spp, "");
    const std::vector<bool> interior = interior_pixels(l.objects);
    size_t edges = 0, checked = 0;
    float worst_alpha = 0.0f, worst_colour = 0.0f;
    for (size_t p = 0; p < l.full.count(); ++p) {
      const std::array<float, 4> m = merged(l.objects_deep, l.room_deep, p);
      worst_alpha = std::max(worst_alpha, std::abs(m[3] - l.full.at(p, "A")));
      // No hole: the room's layer covers every pixel (its wall fills the view), objects or not.
      EXPECT_EQ(l.room.at(p, "A"), 1.0f) << "pixel " << p;
      if (spp == "16" && !interior[p]) {
        ++edges;
        continue;
      }
      ++checked;
      for (int c = 0; c < 3; ++c)
        worst_colour = std::max(worst_colour, relative(m[size_t(c)], l.full.at(p, rgba[c])));
    }
    EXPECT_LE(worst_alpha, 1e-3f) << "spp " << spp;
    EXPECT_LE(worst_colour, 1e-3f) << "spp " << spp;
    EXPECT_GT(checked, l.full.count() / 2) << "spp " << spp;
    EXPECT_LT(edges, l.full.count() / 3) << "spp " << spp;
    if (spp == "16") {
      EXPECT_GT(edges, 0u);
    }
    std::printf(
        "spp %s: merge alpha max error %.3g on all pixels, colour %.3g on %zu interior pixels (%zu edge)\n",
        spp.c_str(), worst_alpha, worst_colour, checked, edges);
    // Each layer names its own objects only: ids, deep ids and the Cryptomatte manifest.
    for (int id : object_ids(l.objects)) EXPECT_TRUE(id == -1 || object_nodes.count(id)) << id;
    for (int id : object_ids(l.room)) EXPECT_TRUE(room_nodes.count(id)) << id;
    for (size_t p = 0; p < l.full.count(); ++p) {
      for (unsigned int k = 0; k < l.objects_deep.counts[p]; ++k)
        EXPECT_TRUE(object_nodes.count(int(l.objects_deep.at(p, k, "id.object"))));
      for (unsigned int k = 0; k < l.room_deep.counts[p]; ++k)
        EXPECT_TRUE(room_nodes.count(int(l.room_deep.at(p, k, "id.object"))));
    }
    const std::string manifest = crypto_object_manifest(l.room);
    EXPECT_NE(manifest.find("room_wall"), std::string::npos) << manifest;
    EXPECT_EQ(manifest.find("obj_"), std::string::npos) << manifest;
    EXPECT_EQ(l.room.spec.get_string_attribute("kiln/others"), "invisible");
  }
}

// The layers as mattes of each other (--others matte) cannot merge by depth: each edge is cut by the
// other's coverage, and the merge cuts it again. So the test above can fail.
TEST(render_layers_cli, deep_matte_layers_do_not_merge_at_edges) {
  const std::string dir = testing::scratch_folder("render_layers_deep_matte");
  const layers l = render_deep_layers(dir, "16", "matte");
  size_t wrong = 0;
  for (size_t p = 0; p < l.full.count(); ++p)
    wrong += std::abs(merged(l.objects_deep, l.room_deep, p)[3] - l.full.at(p, "A")) > 1e-3f;
  EXPECT_GT(wrong, 10u);
  EXPECT_LT(l.room.at(size_t(size / 2 * size + size / 2 - 4), "A"), 1.0f);  // a hole behind the triangle
}

// DeepHoldout of the room by the objects' layer is the flat render of the room with the objects as
// mattes: everywhere at pixel centres; with 16 samples on interior pixels, and on edge pixels whose
// holdout samples all lie in front of the room's (elsewhere a room surface spans the object's
// depth inside the pixel, and a holdout by depth cannot know which of its samples the object hid).
TEST(render_layers_cli, a_deep_holdout_of_one_layer_by_another_is_the_matte_render) {
  for (const std::string spp : {"1", "16"}) {
    const std::string dir = testing::scratch_folder("render_layers_holdout_" + spp);
    const layers l = render_deep_layers(dir, spp, "");
    const channel_exr matte =
        render(write_scene(dir + "/scene.gltf"), dir + "/matte.exr", {"--spp", spp, "--holdout", objects});
    const std::vector<bool> interior = interior_pixels(l.objects);
    float worst = 0.0f, worst_edge_alpha = 0.0f;
    size_t edge_alpha_checked = 0;
    for (size_t p = 0; p < matte.count(); ++p) {
      const std::array<float, 4> h = held_out(l.room_deep, l.objects_deep, p);
      if (spp == "1" || interior[p]) {
        for (int c = 0; c < 4; ++c) worst = std::max(worst, relative(h[size_t(c)], matte.at(p, rgba[c])));
      } else if (holdout_in_front(l.room_deep, l.objects_deep, p)) {
        ++edge_alpha_checked;
        worst_edge_alpha = std::max(worst_edge_alpha, std::abs(h[3] - matte.at(p, "A")));
      }
    }
    EXPECT_LE(worst, 1e-3f) << "spp " << spp;
    EXPECT_LE(worst_edge_alpha, 1e-3f) << "spp " << spp;
    if (spp == "16") {
      EXPECT_GT(edge_alpha_checked, 10u);
    }
  }
}

// Flat layers as documented (--only and --holdout of the same nodes, mattes by default) add to the
// full render on every pixel, edges included, with a filter that spreads samples over neighbouring
// pixels; `over` (each edge cut twice) does not.
TEST(render_layers_cli, flat_layers_add_with_plus_and_over_is_not_their_operation) {
  const std::string dir = testing::scratch_folder("render_layers_flat");
  const std::string scene = write_scene(dir + "/scene.gltf");
  const std::vector<std::string> sampling = {"--spp", "16", "--filter", "gaussian"};
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.end(), sampling.begin(), sampling.end());
    return extra;
  };
  const channel_exr full = render(scene, dir + "/full.exr", sampling);
  const channel_exr a = render(scene, dir + "/objects.exr", with({"--only", objects}));
  const channel_exr b = render(scene, dir + "/room.exr", with({"--holdout", objects}));
  float worst_plus = 0.0f;
  size_t over_wrong = 0;
  for (size_t p = 0; p < full.count(); ++p)
    for (const char* c : rgba) {
      const float want = full.at(p, c);
      worst_plus = std::max(worst_plus, relative(a.at(p, c) + b.at(p, c), want));
      over_wrong += relative(a.at(p, c) + (1.0f - a.at(p, "A")) * b.at(p, c), want) > 1e-3f;
    }
  EXPECT_LE(worst_plus, 1e-5f);
  EXPECT_GT(over_wrong, 20u);
  EXPECT_EQ(b.spec.get_string_attribute("kiln/others"), "matte");
  std::printf("plus: max relative error %.3g; over: %zu channel values off by more than 1e-3\n", worst_plus,
              over_wrong);
}

// Where the room's layer sees an object as a matte (alpha 0), its utility passes hold what a miss
// holds: no id, no depth, no position, normal, uv or albedo of the object.
TEST(render_layers_cli, a_matte_writes_nothing_to_the_layer_s_utility_passes) {
  const std::string dir = testing::scratch_folder("render_layers_passes");
  const std::string scene = write_scene(dir + "/scene.gltf");
  const channel_exr full = render(scene, dir + "/full.exr", {"--spp", "1"});
  const channel_exr room = render(scene, dir + "/room.exr", {"--spp", "1", "--holdout", objects});
  size_t mattes = 0;
  for (size_t p = 0; p < room.count(); ++p) {
    if (room.at(p, "A") != 0.0f) continue;
    ++mattes;
    EXPECT_TRUE(object_nodes.count(int(full.at(p, "id.object"))));  // the full render sees an object
    EXPECT_EQ(room.at(p, "id.object"), -1.0f) << p;
    EXPECT_FALSE(std::isfinite(room.at(p, "Z")) && room.at(p, "Z") < 1e30f) << p;
    for (const char* c : {"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "uv.U", "uv.V", "albedo.R"})
      EXPECT_EQ(room.at(p, c), 0.0f) << p << " " << c;
  }
  EXPECT_GT(mattes, 100u);
}

// The grid backend passes the layer's others by for camera rays as Embree's ray masks do.
TEST(render_layers_cli, every_backend_hides_the_others_from_camera_rays_alike) {
  const std::string dir = testing::scratch_folder("render_layers_backends");
  const std::string scene = write_scene(dir + "/scene.gltf");
  const std::vector<std::string> layer = {"--spp", "4", "--holdout", objects, "--others", "invisible"};
  const channel_exr embree = render(scene, dir + "/embree.exr", layer);
  std::vector<std::string> with_grid = layer;
  with_grid.insert(with_grid.end(), {"--accel", "grid"});
  const channel_exr grid = render(scene, dir + "/grid.exr", with_grid);
  float worst = 0.0f;
  for (size_t p = 0; p < embree.count(); ++p) {
    EXPECT_EQ(embree.at(p, "A"), 1.0f) << p;  // no hole behind the objects
    for (const char* c : rgba) worst = std::max(worst, relative(grid.at(p, c), embree.at(p, c)));
  }
  EXPECT_LE(worst, 1e-4f);
}

TEST(render_layers_cli, invisible_others_and_invisible_holdouts_are_refused_together) {
  const std::string dir = testing::scratch_folder("render_layers_refused");
  const std::string scene = write_scene(dir + "/scene.gltf");
  const auto run = testing::run_kiln({"render", scene, "-o", dir + "/x.exr", "--holdout", objects, "--others",
                                      "invisible", "--holdout-invisible"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.stderr_text.find("--holdout-invisible"), std::string::npos) << run.stderr_text;
  EXPECT_FALSE(std::filesystem::exists(dir + "/x.exr"));
}

}  // namespace
}  // namespace kiln
