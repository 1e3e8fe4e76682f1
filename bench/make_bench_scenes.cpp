// Writes the generated scenes of kiln's benchmark suite as binary glTF (.glb): closed UV spheres
// of about 10k, 100k, 1M and 4M triangles; one 10k- and one 100k-triangle sphere instanced 1000
// times (and the 100k one placed once, the memory baseline); and 10k analytic spheres
// (KILN_quadric) sharing one definition. Each has a camera and a point light, so
// `kiln bench` renders camera and shadow rays on it. A tool, not part of the renderer.
// With --tessellation it writes instead the exact-versus-tessellated set: a sphere, a capped
// cylinder and a torus as KILN_quadric, and as meshes of about 10^2 ... 10^6 triangles, all under
// the same camera and light, so their images can be compared pixel by pixel.
// Usage: make_bench_scenes OUTPUT_FOLDER [--skip-4m | --tessellation]
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "accel/grid/synthetic_scenes.h"

namespace {

using nlohmann::json;

// A .glb: the JSON chunk and one binary chunk holding every accessor.
struct glb_writer {
  json doc;
  std::vector<uint8_t> bin;

  glb_writer() {
    doc["asset"] = {{"version", "2.0"}, {"generator", "kiln make_bench_scenes"}};
    doc["scene"] = 0;
    doc["buffers"] = json::array({json::object()});
    doc["materials"] = json::array(
        {{{"pbrMetallicRoughness",
           {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}}}});
  }

  int add_view(const void* data, size_t bytes, int target) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    bin.resize(offset + bytes);
    std::memcpy(bin.data() + offset, data, bytes);
    doc["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}});
    return int(doc["bufferViews"].size()) - 1;
  }

  int add_mesh(const kiln::mesh& m) {
    std::vector<kiln::vec3> normals;
    for (const kiln::vec3& p : m.positions) normals.push_back(glm::normalize(p));
    return add_mesh(m, normals);
  }

  int add_mesh(const kiln::mesh& m, const std::vector<kiln::vec3>& normals) {
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (const kiln::vec3& p : m.positions)
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
    const int positions = add_view(m.positions.data(), m.positions.size() * sizeof(kiln::vec3), 34962);
    doc["accessors"].push_back({{"bufferView", positions},
                                {"componentType", 5126},
                                {"count", m.positions.size()},
                                {"type", "VEC3"},
                                {"min", {lo[0], lo[1], lo[2]}},
                                {"max", {hi[0], hi[1], hi[2]}}});
    const int position_accessor = int(doc["accessors"].size()) - 1;
    const int normal_view = add_view(normals.data(), normals.size() * sizeof(kiln::vec3), 34962);
    doc["accessors"].push_back(
        {{"bufferView", normal_view}, {"componentType", 5126}, {"count", normals.size()}, {"type", "VEC3"}});
    const int normal_accessor = int(doc["accessors"].size()) - 1;
    const int indices = add_view(m.indices.data(), m.indices.size() * sizeof(uint32_t), 34963);
    doc["accessors"].push_back(
        {{"bufferView", indices}, {"componentType", 5125}, {"count", m.indices.size()}, {"type", "SCALAR"}});
    doc["meshes"].push_back(
        {{"primitives",
          {{{"attributes", {{"POSITION", position_accessor}, {"NORMAL", normal_accessor}}},
            {"indices", int(doc["accessors"].size()) - 1},
            {"material", 0}}}}});
    return int(doc["meshes"].size()) - 1;
  }

  // A camera at `eye` looking at the origin, and a point light above and beside it.
  void add_camera_and_light(double distance, double light_intensity) {
    doc["cameras"].push_back({{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.01}}}});
    const double a = std::atan2(0.4, 1.0);  // camera tilted down toward the origin
    doc["nodes"].push_back({{"camera", 0},
                            {"translation", {0.0, distance * std::sin(a), distance * std::cos(a)}},
                            {"rotation", {-std::sin(a / 2), 0.0, 0.0, std::cos(a / 2)}}});
    doc["extensionsUsed"].push_back("KHR_lights_punctual");
    doc["extensions"]["KHR_lights_punctual"]["lights"] =
        json::array({{{"type", "point"}, {"intensity", light_intensity}}});
    doc["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
                            {"translation", {distance, distance, distance}}});
  }

  void write(const std::string& path) {
    // A file of analytic shapes only has no binary data: no buffer and no BIN chunk.
    if (bin.empty())
      doc.erase("buffers");
    else
      doc["buffers"][0]["byteLength"] = bin.size();
    json nodes = json::array();
    for (size_t i = 0; i < doc["nodes"].size(); ++i) nodes.push_back(i);
    doc["scenes"] = json::array({{{"nodes", nodes}}});
    std::string text = doc.dump();
    while (text.size() % 4) text += ' ';
    while (bin.size() % 4) bin.push_back(0);
    const uint32_t total = uint32_t(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size()));
    std::ofstream out(path, std::ios::binary);
    auto u32 = [&](uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
    u32(0x46546C67);  // "glTF"
    u32(2);
    u32(total);
    u32(uint32_t(text.size()));
    u32(0x4E4F534A);  // "JSON"
    out.write(text.data(), std::streamsize(text.size()));
    if (!bin.empty()) {
      u32(uint32_t(bin.size()));
      u32(0x004E4942);  // "BIN\0"
      out.write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
    }
    std::printf("wrote %s (%.1f MB)\n", path.c_str(), double(total) / 1e6);
  }
};

// rings·segments·2 ≈ triangles, with segments = 2·rings.
kiln::mesh sphere_of(size_t triangles) {
  const int rings = int(std::lround(std::sqrt(double(triangles) / 4.0)));
  return kiln::make_sphere_mesh(rings, 2 * rings, 1.0f);
}

void single_mesh(const std::string& path, size_t triangles) {
  glb_writer w;
  w.doc["nodes"].push_back({{"mesh", w.add_mesh(sphere_of(triangles))}});
  w.add_camera_and_light(3.5, 60.0);
  w.write(path);
}

// n³ copies of one mesh on a lattice, e.g. 1000 placements of 10k triangles.
void instanced(const std::string& path, size_t triangles, int n) {
  glb_writer w;
  const int mesh = w.add_mesh(sphere_of(triangles));
  for (int i = 0; i < n * n * n; ++i) {
    const double x = i % n, y = (i / n) % n, z = i / (n * n);
    w.doc["nodes"].push_back(
        {{"mesh", mesh},
         {"translation", {(x - (n - 1) / 2.0) * 2.5, (y - (n - 1) / 2.0) * 2.5, (z - (n - 1) / 2.0) * 2.5}},
         {"scale", {0.9 + 0.02 * (i % 5), 0.9 + 0.02 * (i % 5), 0.9 + 0.02 * (i % 5)}}});
  }
  w.add_camera_and_light(2.5 * n * 1.6, 60.0 * n * n);
  w.write(path);
}

// count analytic spheres (one KILN_quadric definition) on a jittered grid.
void quadric_spheres(const std::string& path, int count) {
  glb_writer w;
  const int side = int(std::ceil(std::cbrt(double(count))));
  for (int i = 0; i < count; ++i) {
    const double x = i % side, y = (i / side) % side, z = i / (side * side);
    w.doc["nodes"].push_back(
        {{"translation", {(x - side / 2.0) * 0.5, (y - side / 2.0) * 0.5, (z - side / 2.0) * 0.5}},
         {"scale", {0.2, 0.2, 0.2}},
         {"extensions", {{"KILN_quadric", {{"primitive", 0}, {"material", 0}}}}}});
  }
  w.doc["extensionsUsed"].push_back("KILN_quadric");
  w.doc["extensions"]["KILN_quadric"]["primitives"] = json::array({{{"kind", "sphere"}, {"radius", 1.0}}});
  w.add_camera_and_light(side * 0.5 * 1.8, 30.0 * side * side);
  w.write(path);
}

// Smooth-shaded meshes with vertex normals from the exact surface, as an exporter would write.
struct normal_mesh {
  kiln::mesh m;
  std::vector<kiln::vec3> normals;
};

// A capped cylinder of radius 1 over z in [-1, 1]: the side as one band of quads, the caps as fans
// (each cap duplicates its ring, so its normals are flat): 4·segments triangles.
normal_mesh cylinder_of(size_t triangles) {
  const int segments = std::max(3, int(triangles / 4));
  normal_mesh out;
  auto vertex = [&](kiln::vec3 p, kiln::vec3 n) {
    out.m.positions.push_back(p);
    out.normals.push_back(n);
    return uint32_t(out.m.positions.size() - 1);
  };
  const uint32_t top = vertex({0, 0, 1}, {0, 0, 1}), bottom = vertex({0, 0, -1}, {0, 0, -1});
  const uint32_t first = uint32_t(out.m.positions.size());
  for (int i = 0; i < segments; ++i) {
    const float a = float(2.0 * M_PI * i / segments);
    const kiln::vec3 radial(std::cos(a), std::sin(a), 0.0f);
    vertex(radial + kiln::vec3(0, 0, 1), radial);      // side, top ring
    vertex(radial - kiln::vec3(0, 0, 1), radial);      // side, bottom ring
    vertex(radial + kiln::vec3(0, 0, 1), {0, 0, 1});   // top cap ring
    vertex(radial - kiln::vec3(0, 0, 1), {0, 0, -1});  // bottom cap ring
  }
  for (int i = 0; i < segments; ++i) {
    const uint32_t a = first + 4 * uint32_t(i), b = first + 4 * uint32_t((i + 1) % segments);
    out.m.indices.insert(out.m.indices.end(), {a + 1, b + 1, b, a + 1, b, a});  // side, outward
    out.m.indices.insert(out.m.indices.end(), {top, a + 2, b + 2});
    out.m.indices.insert(out.m.indices.end(), {bottom, b + 3, a + 3});
  }
  return out;
}

// A torus of major radius 1 and minor radius 0.35 about z: a u×v grid with u = 2v, 2uv triangles.
normal_mesh torus_of(size_t triangles) {
  const int v_count = std::max(3, int(std::lround(std::sqrt(double(triangles) / 4.0))));
  const int u_count = 2 * v_count;
  const float major = 1.0f, minor = 0.35f;
  normal_mesh out;
  for (int i = 0; i < u_count; ++i)
    for (int j = 0; j < v_count; ++j) {
      const float u = float(2.0 * M_PI * i / u_count), v = float(2.0 * M_PI * j / v_count);
      const kiln::vec3 ring(std::cos(u), std::sin(u), 0.0f);
      const kiln::vec3 n = ring * std::cos(v) + kiln::vec3(0, 0, std::sin(v));
      out.m.positions.push_back(ring * major + n * minor);
      out.normals.push_back(n);
    }
  auto index = [&](int i, int j) { return uint32_t((i % u_count) * v_count + (j % v_count)); };
  for (int i = 0; i < u_count; ++i)
    for (int j = 0; j < v_count; ++j)
      out.m.indices.insert(out.m.indices.end(), {index(i, j), index(i + 1, j), index(i + 1, j + 1),
                                                 index(i, j), index(i + 1, j + 1), index(i, j + 1)});
  return out;
}

// The shape tilted toward the camera so the cylinder shows a cap and the torus its hole.
json tilted_node() {
  const double a = 0.6;
  return {{"rotation", {std::sin(a / 2), 0.0, 0.0, std::cos(a / 2)}}};
}

void quadric_shape(const std::string& path, const json& definition) {
  glb_writer w;
  json node = tilted_node();
  node["extensions"] = {{"KILN_quadric", {{"primitive", 0}, {"material", 0}}}};
  w.doc["nodes"].push_back(node);
  w.doc["extensionsUsed"].push_back("KILN_quadric");
  w.doc["extensions"]["KILN_quadric"]["primitives"] = json::array({definition});
  w.add_camera_and_light(4.0, 60.0);
  w.write(path);
}

void mesh_shape(const std::string& path, const normal_mesh& shape) {
  glb_writer w;
  json node = tilted_node();
  node["mesh"] = w.add_mesh(shape.m, shape.normals);
  w.doc["nodes"].push_back(node);
  w.add_camera_and_light(4.0, 60.0);
  w.write(path);
}

void tessellation_set(const std::filesystem::path& folder) {
  quadric_shape((folder / "sphere_quadric.glb").string(), {{"kind", "sphere"}, {"radius", 1.0}});
  quadric_shape((folder / "cylinder_quadric.glb").string(),
                {{"kind", "cylinder"}, {"radius", 1.0}, {"zmin", -1.0}, {"zmax", 1.0}, {"caps", true}});
  quadric_shape((folder / "torus_quadric.glb").string(),
                {{"kind", "torus"}, {"major_radius", 1.0}, {"minor_radius", 0.35}});
  for (size_t n : {100, 1000, 10000, 100000, 1000000}) {
    const std::string suffix = "_mesh_" + std::to_string(n) + ".glb";
    kiln::mesh sphere = sphere_of(n);
    std::vector<kiln::vec3> normals;
    for (const kiln::vec3& p : sphere.positions) normals.push_back(glm::normalize(p));
    mesh_shape((folder / ("sphere" + suffix)).string(), {sphere, normals});
    mesh_shape((folder / ("cylinder" + suffix)).string(), cylinder_of(n));
    mesh_shape((folder / ("torus" + suffix)).string(), torus_of(n));
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: make_bench_scenes OUTPUT_FOLDER [--skip-4m | --tessellation]\n");
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  const std::string mode = argc > 2 ? argv[2] : "";
  const bool skip_4m = mode == "--skip-4m";
  std::filesystem::create_directories(folder);
  if (mode == "--tessellation") {
    tessellation_set(folder);
    return 0;
  }
  single_mesh((folder / "mesh_10k.glb").string(), 10000);
  single_mesh((folder / "mesh_100k.glb").string(), 100000);
  single_mesh((folder / "mesh_1m.glb").string(), 1000000);
  if (!skip_4m) single_mesh((folder / "mesh_4m.glb").string(), 4000000);
  instanced((folder / "instanced_1000x10k.glb").string(), 10000, 10);
  // The memory check: 1000 placements of the 100k mesh against one placement of it.
  instanced((folder / "instanced_1x100k.glb").string(), 100000, 1);
  instanced((folder / "instanced_1000x100k.glb").string(), 100000, 10);
  quadric_spheres((folder / "quadric_spheres_10k.glb").string(), 10000);
  return 0;
}
