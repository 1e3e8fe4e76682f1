// EXT_meshopt_compression: a small animated asset (a UV sphere, rotated by an animation) is
// written twice, plainly and compressed with meshoptimizer's own encoders (vertex codec with the
// EXPONENTIAL, OCTAHEDRAL and QUATERNION filters, the TRIANGLES and INDICES index codecs, a
// fallback buffer without data), and both must load to the same scene within what each filter's
// quantisation allows, and trace the same image. Broken streams are refused with their pointer.
#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "accel/embree/embree_accelerator.h"
#include "core/error.h"
#include "io/gltf/gltf_loader.h"
#include "support/gltf_builder.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::base64_encode;
using testing::gltf_builder;

constexpr int k_short = 5122, k_byte = 5120, k_ushort = 5123, k_uint = 5125, k_float = 5126;

struct sphere {
  std::vector<float> positions, normals, texcoords;  // 3, 3, 2 per vertex
  std::vector<uint32_t> indices;
};

sphere make_sphere(int rings, int segments) {
  sphere s;
  for (int r = 0; r <= rings; ++r)
    for (int g = 0; g <= segments; ++g) {
      const double theta = M_PI * r / rings, phi = 2.0 * M_PI * g / segments;
      // Exact poles: sin(pi) is 1.2e-16, which would give the pole's triangles an area that the
      // EXPONENTIAL filter's shared exponent rounds away (and the loader then drops them).
      const double sin_theta = r == 0 || r == rings ? 0.0 : std::sin(theta);
      const double n[3] = {sin_theta * std::cos(phi), std::cos(theta), sin_theta * std::sin(phi)};
      for (int k = 0; k < 3; ++k) {
        s.positions.push_back(float(0.75 * n[k] + (k == 0 ? 0.3 : 0.0)));
        s.normals.push_back(float(n[k]));
      }
      s.texcoords.push_back(float(g) / segments);
      s.texcoords.push_back(float(r) / rings);
    }
  for (int r = 0; r < rings; ++r)
    for (int g = 0; g < segments; ++g) {
      const uint32_t a = uint32_t(r * (segments + 1) + g), b = a + uint32_t(segments + 1);
      for (uint32_t i : {a, b, a + 1, a + 1, b, b + 1}) s.indices.push_back(i);
    }
  return s;
}

// Key frames of the animation: a turn about y, as quaternions (x, y, z, w).
const std::vector<float> key_times = {0.0f, 1.0f, 2.0f};
std::vector<float> key_rotations() {
  std::vector<float> q;
  for (float t : key_times) {
    const double half = 0.5 * 1.2 * t;
    for (double v : {0.0, std::sin(half), 0.0, std::cos(half)}) q.push_back(float(v));
  }
  return q;
}

// The animated node, its mesh and animation; accessors are given by index.
void finish_document(gltf_builder& b, int pos, int nrm, int uv, int idx, int idx16, int times,
                     int rotations) {
  const json attributes = {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}};
  b.doc["meshes"] = json::array(
      {json{{"primitives", json::array({json{{"attributes", attributes}, {"indices", idx}},
                                        json{{"attributes", attributes}, {"indices", idx16}}})}}});
  b.doc["accessors"][size_t(pos)]["min"] = {-0.45, -0.75, -0.75};
  b.doc["accessors"][size_t(pos)]["max"] = {1.05, 0.75, 0.75};
  const int node = b.add_node({{"mesh", 0}});
  b.set_scene({node});
  b.doc["animations"] = json::array(
      {json{{"samplers", json::array({json{{"input", times}, {"output", rotations}}})},
            {"channels",
             json::array({json{{"sampler", 0}, {"target", {{"node", node}, {"path", "rotation"}}}}})}}});
}

std::string write_original(const sphere& s, const std::string& path) {
  gltf_builder b;
  const int pos = b.add_data(s.positions, k_float, "VEC3", 3);
  const int nrm = b.add_data(s.normals, k_float, "VEC3", 3);
  const int uv = b.add_data(s.texcoords, k_float, "VEC2", 2);
  const int idx = b.add_data(s.indices, k_uint, "SCALAR", 1);
  std::vector<uint16_t> idx16(s.indices.begin(), s.indices.end());
  std::reverse(idx16.begin(), idx16.end());  // the same triangles, another order for the sequence codec
  const int second = b.add_data(idx16, k_ushort, "SCALAR", 1);
  const int times = b.add_data(key_times, k_float, "SCALAR", 1);
  b.doc["accessors"][size_t(times)]["min"] = {0.0};
  b.doc["accessors"][size_t(times)]["max"] = {2.0};
  const int rotations = b.add_data(key_rotations(), k_float, "VEC4", 4);
  finish_document(b, pos, nrm, uv, idx, second, times, rotations);
  return b.write(path);
}

enum class codec { attributes, triangles, indices };

// Encodes `decoded` (count elements of `stride` bytes) and adds the compressed bytes as a
// bufferView of buffer 0 that the extension names; the view itself lies in fallback buffer 1.
struct compressed_writer {
  gltf_builder b;
  size_t fallback_bytes = 0;

  int add(const std::vector<uint8_t>& decoded, size_t count, size_t stride, codec mode, const char* filter,
          bool vertex_stride = false) {
    std::vector<uint8_t> packed;
    if (mode == codec::attributes) {
      packed.resize(meshopt_encodeVertexBufferBound(count, stride));
      packed.resize(meshopt_encodeVertexBuffer(packed.data(), packed.size(), decoded.data(), count, stride));
    } else {
      std::vector<uint32_t> idx(count);
      for (size_t i = 0; i < count; ++i)
        idx[i] = stride == 2 ? uint32_t(decoded[2 * i] | decoded[2 * i + 1] << 8)
                             : uint32_t(decoded[4 * i] | decoded[4 * i + 1] << 8 | decoded[4 * i + 2] << 16 |
                                        uint32_t(decoded[4 * i + 3]) << 24);
      if (mode == codec::triangles) {
        packed.resize(meshopt_encodeIndexBufferBound(count, count));
        packed.resize(meshopt_encodeIndexBuffer(packed.data(), packed.size(), idx.data(), count));
      } else {
        packed.resize(meshopt_encodeIndexSequenceBound(count, count));
        packed.resize(meshopt_encodeIndexSequence(packed.data(), packed.size(), idx.data(), count));
      }
    }
    const int view = b.add_view(packed.data(), packed.size());
    json& v = b.doc["bufferViews"][size_t(view)];
    const json ext = {{"buffer", 0},
                      {"byteOffset", v["byteOffset"]},
                      {"byteLength", packed.size()},
                      {"byteStride", stride},
                      {"count", count},
                      {"mode", mode == codec::attributes  ? "ATTRIBUTES"
                               : mode == codec::triangles ? "TRIANGLES"
                                                          : "INDICES"},
                      {"filter", filter}};
    v = {{"buffer", 1}, {"byteOffset", fallback_bytes}, {"byteLength", count * stride}};
    if (vertex_stride) v["byteStride"] = stride;
    v["extensions"] = {{"EXT_meshopt_compression", ext}};
    fallback_bytes += (count * stride + 3) / 4 * 4;
    return view;
  }
};

template <typename T>
std::vector<uint8_t> bytes_of(const std::vector<T>& values) {
  std::vector<uint8_t> out(values.size() * sizeof(T));
  std::memcpy(out.data(), values.data(), out.size());
  return out;
}

// The compressed document (buffer 0: the compressed bytes, buffer 1: the fallback) and buffer 0.
struct compressed_asset {
  json doc;
  std::vector<uint8_t> bin;
};

compressed_asset compress(const sphere& s) {
  compressed_writer w;
  gltf_builder& b = w.b;
  const size_t n = s.positions.size() / 3;
  // Positions: EXPONENTIAL (a shared exponent per vertex, 24-bit mantissas): floats again.
  std::vector<uint32_t> exp(n * 3);
  meshopt_encodeFilterExp(exp.data(), n, 12, 24, s.positions.data());
  const int pos =
      b.add_accessor(w.add(bytes_of(exp), n, 12, codec::attributes, "EXPONENTIAL", true), k_float, n, "VEC3");
  // Normals: OCTAHEDRAL, 8-bit signed normalised x y z and a w the filter keeps.
  std::vector<float> n4;
  for (size_t i = 0; i < n; ++i)
    n4.insert(n4.end(), {s.normals[3 * i], s.normals[3 * i + 1], s.normals[3 * i + 2], 1.0f});
  std::vector<int8_t> oct(n * 4);
  meshopt_encodeFilterOct(oct.data(), n, 4, 8, n4.data());
  const int nrm = b.add_accessor(w.add(bytes_of(oct), n, 4, codec::attributes, "OCTAHEDRAL", true), k_byte, n,
                                 "VEC3", 0, true);
  const int uv =
      b.add_accessor(w.add(bytes_of(s.texcoords), n, 8, codec::attributes, "NONE", true), k_float, n, "VEC2");
  const size_t m = s.indices.size();
  const int idx =
      b.add_accessor(w.add(bytes_of(s.indices), m, 4, codec::triangles, "NONE"), k_uint, m, "SCALAR");
  std::vector<uint16_t> idx16(s.indices.begin(), s.indices.end());
  std::reverse(idx16.begin(), idx16.end());
  const int second =
      b.add_accessor(w.add(bytes_of(idx16), m, 2, codec::indices, "NONE"), k_ushort, m, "SCALAR");
  const int times = b.add_accessor(w.add(bytes_of(key_times), key_times.size(), 4, codec::attributes, "NONE"),
                                   k_float, key_times.size(), "SCALAR");
  b.doc["accessors"][size_t(times)]["min"] = {0.0};
  b.doc["accessors"][size_t(times)]["max"] = {2.0};
  // Rotations: QUATERNION, three 12-bit components and the index of the largest one.
  std::vector<int16_t> quat(key_times.size() * 4);
  meshopt_encodeFilterQuat(quat.data(), key_times.size(), 8, 12, key_rotations().data());
  const int rotations =
      b.add_accessor(w.add(bytes_of(quat), key_times.size(), 8, codec::attributes, "QUATERNION"), k_short,
                     key_times.size(), "VEC4", 0, true);
  finish_document(b, pos, nrm, uv, idx, second, times, rotations);
  b.doc["extensionsUsed"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
  b.doc["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
  json doc = b.finished("");
  doc["buffers"].push_back({{"byteLength", w.fallback_bytes},
                            {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
  return {doc, b.bin};
}

std::string write_compressed(const sphere& s, const std::string& path) {
  compressed_asset c = compress(s);
  c.doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64_encode(c.bin);
  std::ofstream(path) << c.doc.dump(1);
  return path;
}

// The same as a .glb: buffer 0 in the BIN chunk, the fallback buffer still without a uri.
std::string write_compressed_glb(const sphere& s, const std::string& path) {
  const compressed_asset c = compress(s);
  std::string text = c.doc.dump();
  while (text.size() % 4 != 0) text += ' ';
  std::vector<uint8_t> bin = c.bin;
  while (bin.size() % 4 != 0) bin.push_back(0);
  std::string out;
  const auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  out += "glTF";
  u32(2);
  u32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  u32(uint32_t(text.size()));
  out += "JSON" + text;
  u32(uint32_t(bin.size()));
  out.append("BIN\0", 4);
  out.append(reinterpret_cast<const char*>(bin.data()), bin.size());
  std::ofstream(path, std::ios::binary) << out;
  return path;
}

struct files {
  fs::path folder = fs::temp_directory_path() / ("kiln_meshopt_" + std::to_string(::getpid()));
  files() { fs::create_directories(folder); }
  ~files() { fs::remove_all(folder); }
  std::string at(const char* name) const { return (folder / name).string(); }
};

// Each triangle's corners rotated so that its smallest index comes first.
std::vector<uint32_t> rotated_to_smallest(std::vector<uint32_t> idx) {
  for (size_t t = 0; t + 2 < idx.size(); t += 3)
    while (idx[t] > idx[t + 1] || idx[t] > idx[t + 2])
      std::rotate(idx.begin() + long(t), idx.begin() + long(t) + 1, idx.begin() + long(t) + 3);
  return idx;
}

scene load_at(const std::string& path, double time) {
  gltf_load_options options;
  options.time = time;
  return load_gltf(path, options);
}

TEST(meshopt, compressed_asset_loads_like_its_original) {
  files f;
  const sphere s = make_sphere(12, 24);
  const std::string original = write_original(s, f.at("original.gltf"));
  const std::string compressed = write_compressed(s, f.at("compressed.gltf"));
  for (const double time : {0.0, 0.7}) {
    SCOPED_TRACE("time " + std::to_string(time));
    const scene a = load_at(original, time), c = load_at(compressed, time);
    ASSERT_EQ(c.meshes.size(), a.meshes.size());
    ASSERT_EQ(c.instances.size(), a.instances.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
      // The index codecs are lossless up to rotating a triangle's corners (winding kept).
      const std::vector<uint32_t> ci = rotated_to_smallest(c.meshes[i].indices),
                                  ai = rotated_to_smallest(a.meshes[i].indices);
      ASSERT_EQ(ci.size(), ai.size());
      for (size_t k = 0; k < ai.size(); ++k)
        ASSERT_EQ(ci[k], ai[k]) << "mesh " << i << " index " << k << " of " << ai.size();
      ASSERT_EQ(c.meshes[i].positions.size(), a.meshes[i].positions.size());
      ASSERT_EQ(c.meshes[i].normals.size(), a.meshes[i].positions.size());
      ASSERT_EQ(c.meshes[i].texcoords0, a.meshes[i].texcoords0);
      for (size_t v = 0; v < a.meshes[i].positions.size(); ++v) {
        // 24-bit mantissas with the vertex's largest exponent: 2^-23 of 1.05 at worst.
        EXPECT_LE(glm::length(c.meshes[i].positions[v] - a.meshes[i].positions[v]), 2e-7f);
        // 8-bit octahedral normals: about 1/127 of a radian at worst.
        EXPECT_LE(glm::length(c.meshes[i].normals[v] - a.meshes[i].normals[v]), 0.02f);
      }
    }
    // 12-bit quaternion components: the turned instance differs by about 1e-3.
    for (size_t i = 0; i < a.instances.size(); ++i)
      for (int col = 0; col < 4; ++col)
        EXPECT_LE(glm::length(c.instances[i].world_from_object[col] - a.instances[i].world_from_object[col]),
                  2e-3);
    // And the same picture: coverage and depth of a 96x96 view. At t = 0 the rotation is the
    // identity (exact in the QUATERNION filter) and only the positions' 2e-7 remains; turned,
    // 12-bit components tilt the sphere by up to ~3.5e-4 rad, which moves depth by ~4e-4 where the
    // view meets the surface squarely and more where it grazes.
    embree_accelerator ea(a), ec(c);
    size_t hits = 0, coverage_changes = 0;
    std::vector<double> depth;
    for (int y = 0; y < 96; ++y)
      for (int x = 0; x < 96; ++x) {
        ray r;
        r.origin = vec3(0.3f, 0.2f, 3.0f);
        r.direction = glm::normalize(vec3((x + 0.5f) / 96 - 0.5f, 0.5f - (y + 0.5f) / 96, -1.0f));
        const std::optional<hit> ha = ea.intersect(r), hc = ec.intersect(r);
        hits += ha.has_value();
        coverage_changes += ha.has_value() != hc.has_value();
        if (ha && hc) depth.push_back(std::abs(double(ha->t) - double(hc->t)));
      }
    std::sort(depth.begin(), depth.end());
    ASSERT_FALSE(depth.empty());
    const double median = depth[depth.size() / 2], worst = depth.back();
    std::printf("t=%g: %zu hits, %zu coverage changes, |dt| median %.2g, worst %.2g\n", time, hits,
                coverage_changes, median, worst);
    EXPECT_GT(hits, 96u * 96u / 10);
    if (time == 0.0) {
      EXPECT_EQ(coverage_changes, 0u);
      EXPECT_LE(worst, 1e-5);
    } else {
      EXPECT_LE(coverage_changes, hits / 100);
      EXPECT_LE(median, 1e-3);
      EXPECT_LE(worst, 1e-2);
    }
  }
}

TEST(meshopt, compressed_glb_loads_like_the_gltf) {
  files f;
  const sphere s = make_sphere(8, 12);
  const scene a = load_at(write_compressed(s, f.at("compressed.gltf")), 0.0);
  const scene c = load_at(write_compressed_glb(s, f.at("compressed.glb")), 0.0);
  ASSERT_EQ(c.meshes.size(), a.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    EXPECT_EQ(c.meshes[i].indices, a.meshes[i].indices);
    EXPECT_EQ(c.meshes[i].positions, a.meshes[i].positions);
    EXPECT_EQ(c.meshes[i].normals, a.meshes[i].normals);
  }
}

std::string error_of(const std::string& path) {
  try {
    load_gltf(path);
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::input);
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    return e.what();
  }
  ADD_FAILURE() << "loaded";
  return "";
}

TEST(meshopt, corrupt_stream_is_refused_with_its_pointer) {
  files f;
  const std::string path = write_compressed(make_sphere(6, 8), f.at("compressed.gltf"));
  json doc = json::parse(std::ifstream(path));
  // Cut the position stream short: the decoder runs out of bytes.
  doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 9;
  std::ofstream(f.at("short.gltf")) << doc.dump();
  const std::string message = error_of(f.at("short.gltf"));
  EXPECT_NE(message.find("/bufferViews/0/extensions/EXT_meshopt_compression: corrupt meshopt stream"),
            std::string::npos)
      << message;
}

TEST(meshopt, plain_view_of_the_fallback_buffer_is_refused) {
  files f;
  const std::string path = write_compressed(make_sphere(6, 8), f.at("compressed.gltf"));
  json doc = json::parse(std::ifstream(path));
  doc["bufferViews"][2].erase("extensions");  // texcoords now read the fallback buffer itself
  std::ofstream(f.at("plain.gltf")) << doc.dump();
  const std::string message = error_of(f.at("plain.gltf"));
  EXPECT_NE(message.find("/bufferViews/2/buffer: reads /buffers/1, a meshopt fallback buffer"),
            std::string::npos)
      << message;
}

TEST(meshopt, filter_stride_is_checked) {
  files f;
  const std::string path = write_compressed(make_sphere(6, 8), f.at("compressed.gltf"));
  json doc = json::parse(std::ifstream(path));
  doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["filter"] = "QUATERNION";  // stride 12
  std::ofstream(f.at("stride.gltf")) << doc.dump();
  const std::string message = error_of(f.at("stride.gltf"));
  EXPECT_NE(
      message.find("/bufferViews/0/extensions/EXT_meshopt_compression/byteStride: is 12, which the filter"),
      std::string::npos)
      << message;
}

// tinygltf keeps an extension's integers in an int: 2^32 + n read as n, so a count or byteStride
// past 32 bits decoded as its low bits and the file loaded. It is refused, naming the member.
TEST(meshopt, counts_and_strides_past_32_bits_are_refused) {
  files f;
  const std::string path = write_compressed(make_sphere(6, 8), f.at("compressed.gltf"));
  const json doc = json::parse(std::ifstream(path));
  const std::string at = "/bufferViews/0/extensions/EXT_meshopt_compression/";
  for (const char* key : {"count", "byteStride", "byteLength", "byteOffset"}) {
    json wide = doc;
    json& member = wide["bufferViews"][0]["extensions"]["EXT_meshopt_compression"][key];
    const uint64_t value = member.get<uint64_t>() + (uint64_t(1) << 32);
    member = value;
    std::ofstream(f.at("wide.gltf")) << wide.dump();
    const std::string message = error_of(f.at("wide.gltf"));
    EXPECT_NE(message.find(at + key + ": " + key + " is " + std::to_string(value) +
                           ", larger than kiln reads (at most 2147483647)"),
              std::string::npos)
        << message;
  }
  json wide = doc;
  wide["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["buffer"] = (uint64_t(1) << 32) + 1;
  std::ofstream(f.at("wide.gltf")) << wide.dump();
  const std::string message = error_of(f.at("wide.gltf"));
  EXPECT_NE(message.find(at + "buffer: /buffers/4294967297 does not exist"), std::string::npos) << message;
}

// A stream declaring more than its bytes can decode to (an 11 KB file once allocated 3 GB before
// the decoder found the stream corrupt) is refused before the output is allocated: by the codecs'
// best ratios, 64:1 for attributes, a byte per triangle, a byte per index.
TEST(meshopt, counts_past_what_the_stream_can_decode_to_are_refused_before_allocating) {
  files f;
  const std::string path = write_compressed(make_sphere(6, 8), f.at("compressed.gltf"));
  const json doc = json::parse(std::ifstream(path));
  for (const int view : {0, 3, 4}) {  // positions (attributes), triangles, indices
    json huge = doc;
    json& ext = huge["bufferViews"][view]["extensions"]["EXT_meshopt_compression"];
    const uint64_t stride = ext["byteStride"], length = ext["byteLength"];
    const uint64_t count = (uint64_t(1) << 30) / stride / 3 * 3;  // a gigabyte of output, whole triangles
    ext["count"] = count;
    huge["bufferViews"][view]["byteLength"] = count * stride;
    std::ofstream(f.at("huge.gltf")) << huge.dump();
    const std::string message = error_of(f.at("huge.gltf"));
    EXPECT_NE(
        message.find("/bufferViews/" + std::to_string(view) + "/extensions/EXT_meshopt_compression: count " +
                     std::to_string(count) + " x byteStride " + std::to_string(stride) + " is " +
                     std::to_string(count * stride) + " bytes, more than the " + std::to_string(length) +
                     "-byte meshopt stream can decode to"),
        std::string::npos)
        << message;
  }
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  EXPECT_LT(usage.ru_maxrss, 512 * 1024) << "peak KiB";  // each output alone is 1 GiB
}

}  // namespace
}  // namespace kiln
