// libFuzzer target: extreme numbers where rays are made. The input's bytes choose a node's
// transform (TRS or a matrix), a child's scale, the mesh's coordinates, a sphere's radius and the
// camera (perspective or orthographic, its node's translation), each number drawn from the whole
// double range (1e-350 to 1e350, so denormals, overflow to infinity and JSON's null all occur).
// The asset then goes through the whole render job at 4x3 pixels, Embree included. The only
// acceptable outcomes are an image or a kiln::error: Embree's assertion on a ray it cannot take
// (abort), a crash or a sanitizer report is a finding.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/error.h"
#include "job/render_job.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path folder;

// Reads numbers from the input, two bytes each: a mantissa byte (with the sign) and a decimal
// exponent byte; past the end, the defaults the caller gives.
struct number_reader {
  const uint8_t* data;
  size_t size;
  size_t at = 0;

  bool has(size_t bytes) const { return at + bytes <= size; }
  uint8_t byte(uint8_t fallback) { return has(1) ? data[at++] : fallback; }
  double number(double fallback) {
    if (!has(2)) return fallback;
    const uint8_t m = data[at++], e = data[at++];
    const double mantissa = (1.0 + double(m & 0x7f) / 128.0) * ((m & 0x80) ? -1.0 : 1.0);
    const int exponent = int(e) * 700 / 255 - 350;  // -350 .. 350
    if (exponent == -350) return 0.0;
    return mantissa * std::pow(10.0, double(exponent));
  }
  json numbers(std::initializer_list<double> fallback) {
    json out = json::array();
    for (double f : fallback) out.push_back(number(f));
    return out;
  }
};

// One triangle, its three float positions written to tri.bin.
void write_triangle(number_reader& in) {
  const double s = in.number(1.0);
  float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (float& p : positions) p = float(double(p) * s);
  std::ofstream out(folder / "tri.bin", std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(positions), sizeof(positions));
}

json make_asset(number_reader& in) {
  const uint8_t flags = in.byte(0);
  write_triangle(in);
  json node = {{"mesh", 0}};
  if (flags & 1) {
    node["matrix"] = in.numbers({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
  } else {
    node["translation"] = in.numbers({0, 0, 0});
    node["rotation"] = in.numbers({0, 0, 0, 1});
    node["scale"] = in.numbers({1, 1, 1});
  }
  json nodes = json::array({node});
  json roots = json::array({0});
  json doc = {{"asset", {{"version", "2.0"}}},
              {"buffers", {{{"uri", "tri.bin"}, {"byteLength", 36}}}},
              {"bufferViews", {{{"buffer", 0}, {"byteLength", 36}}}},
              {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}}},
              {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}}};
  if (flags & 2) {  // a sphere under the first node, placed by its own scale
    doc["extensionsUsed"] = {"KILN_quadric"};
    doc["extensions"]["KILN_quadric"]["primitives"] = {{{"kind", "sphere"}, {"radius", in.number(1.0)}}};
    nodes.push_back(
        {{"scale", in.numbers({1, 1, 1})}, {"extensions", {{"KILN_quadric", {{"primitive", 0}}}}}});
    nodes[0]["children"] = {1};
  }
  if (flags & 4) {  // a camera of the file's own
    json camera;
    if (flags & 8)
      camera = {
          {"type", "orthographic"},
          {"orthographic", {{"xmag", in.number(1)}, {"ymag", in.number(1)}, {"znear", 0.01}, {"zfar", 100}}}};
    else
      camera = {{"type", "perspective"},
                {"perspective", {{"yfov", in.number(0.8)}, {"znear", in.number(0.01)}}}};
    doc["cameras"] = {camera};
    nodes.push_back({{"camera", 0}, {"translation", in.numbers({0, 0, 3})}});
    roots.push_back(nodes.size() - 1);
  }
  doc["nodes"] = nodes;
  doc["scenes"] = {{{"nodes", roots}}};
  doc["scene"] = 0;
  return doc;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  folder = fs::temp_directory_path() / ("kiln_fuzz_transforms_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  number_reader in{data, size};
  const std::string asset = (folder / "asset.gltf").string();
  {
    std::ofstream out(asset, std::ios::trunc);
    out << make_asset(in).dump();
  }
  kiln::render_job job;
  job.options.input = asset;
  job.options.output = (folder / "out.exr").string();
  job.options.width = 4;
  job.options.height = 3;
  job.options.samples_per_pixel = 1;
  job.options.threads = 1;
  try {
    (void)kiln::run_job(job);
  } catch (const kiln::error&) {
    // A clear refusal is an expected outcome.
  }
  return 0;
}
