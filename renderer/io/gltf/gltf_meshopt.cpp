#include "io/gltf/gltf_meshopt.h"

#include <meshoptimizer.h>

#include <utility>
#include <vector>

#include "core/error.h"
#include "core/memory_budget.h"
#include "io/gltf/gltf_common.h"

namespace kiln::gltf_internal {
namespace {

using json = nlohmann::json;

// The placeholder a fallback buffer parses with: four zero bytes.
constexpr const char* placeholder_uri = "data:application/octet-stream;base64,AAAAAA==";

enum class meshopt_mode { attributes, triangles, indices };
enum class meshopt_filter { none, octahedral, quaternion, exponential };

// The extension object of one bufferView, read and range-checked.
struct meshopt_view {
  int buffer = -1;
  uint64_t offset = 0, length = 0, stride = 0, count = 0;
  meshopt_mode mode = meshopt_mode::attributes;
  meshopt_filter filter = meshopt_filter::none;
};

bool is_fallback(const tinygltf::Buffer& buffer) {
  auto it = buffer.extensions.find(meshopt_extension);
  return it != buffer.extensions.end() && it->second.IsObject() && it->second.Get("fallback").IsBool() &&
         it->second.Get("fallback").Get<bool>();
}

// A non-negative integer member; `fallback` when absent (-1: required).
uint64_t integer_member(const tinygltf::Value& ext, const char* key, int64_t fallback,
                        const std::string& file, const std::string& where) {
  if (!ext.Has(key)) {
    if (fallback >= 0) return static_cast<uint64_t>(fallback);
    throw input_error(file, pointer_join(where, key), "is required");
  }
  const tinygltf::Value& v = ext.Get(key);
  const double d = v.IsNumber() || v.IsInt() ? v.GetNumberAsDouble() : -1.0;
  if (!(d >= 0 && d <= 9007199254740992.0) || d != static_cast<double>(static_cast<uint64_t>(d)))
    throw input_error(file, pointer_join(where, key), "must be an integer >= 0");
  return static_cast<uint64_t>(d);
}

std::string string_member(const tinygltf::Value& ext, const char* key, const char* fallback) {
  if (!ext.Has(key)) return fallback;
  const tinygltf::Value& v = ext.Get(key);
  return v.IsString() ? v.Get<std::string>() : std::string("(not a string)");
}

meshopt_mode read_mode(const tinygltf::Value& ext, const std::string& file, const std::string& where) {
  if (!ext.Has("mode")) throw input_error(file, pointer_join(where, "mode"), "is required");
  const std::string mode = string_member(ext, "mode", "");
  if (mode == "ATTRIBUTES") return meshopt_mode::attributes;
  if (mode == "TRIANGLES") return meshopt_mode::triangles;
  if (mode == "INDICES") return meshopt_mode::indices;
  throw input_error(file, pointer_join(where, "mode"),
                    "is " + quoted(mode) + "; expected ATTRIBUTES, TRIANGLES or INDICES");
}

meshopt_filter read_filter(const tinygltf::Value& ext, const std::string& file, const std::string& where) {
  const std::string filter = string_member(ext, "filter", "NONE");
  if (filter == "NONE") return meshopt_filter::none;
  if (filter == "OCTAHEDRAL") return meshopt_filter::octahedral;
  if (filter == "QUATERNION") return meshopt_filter::quaternion;
  if (filter == "EXPONENTIAL") return meshopt_filter::exponential;
  throw input_error(file, pointer_join(where, "filter"),
                    "is " + quoted(filter) + "; expected NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
}

// The strides each mode and filter allow (the extension's specification and the decoder's).
void check_stride(const meshopt_view& v, const std::string& file, const std::string& where) {
  const std::string stride_where = pointer_join(where, "byteStride");
  const std::string stride = std::to_string(v.stride);
  if (v.mode == meshopt_mode::attributes) {
    if (v.stride == 0 || v.stride % 4 != 0 || v.stride > 256)
      throw input_error(file, stride_where, "is " + stride + "; ATTRIBUTES need a multiple of 4 up to 256");
  } else {
    if (v.stride != 2 && v.stride != 4)
      throw input_error(file, stride_where, "is " + stride + "; indices need 2 or 4");
    if (v.filter != meshopt_filter::none)
      throw input_error(file, pointer_join(where, "filter"), "a filter applies to ATTRIBUTES only");
    if (v.mode == meshopt_mode::triangles && v.count % 3 != 0)
      throw input_error(file, pointer_join(where, "count"), "TRIANGLES need a multiple of 3 indices");
  }
  const bool ok = v.filter == meshopt_filter::none ||
                  (v.filter == meshopt_filter::octahedral && (v.stride == 4 || v.stride == 8)) ||
                  (v.filter == meshopt_filter::quaternion && v.stride == 8) ||
                  v.filter == meshopt_filter::exponential;
  if (!ok) throw input_error(file, stride_where, "is " + stride + ", which the filter does not allow");
}

meshopt_view read_extension(const tinygltf::Model& model, const tinygltf::Value& ext, const std::string& file,
                            const std::string& where) {
  if (!ext.IsObject()) throw input_error(file, where, "the extension must be an object");
  meshopt_view v;
  const uint64_t buffer = integer_member(ext, "buffer", -1, file, where);
  if (buffer >= model.buffers.size())
    throw input_error(file, pointer_join(where, "buffer"),
                      "/buffers/" + std::to_string(buffer) + " does not exist (file has " +
                          std::to_string(model.buffers.size()) + " buffers)");
  v.buffer = static_cast<int>(buffer);
  v.offset = integer_member(ext, "byteOffset", 0, file, where);
  v.length = integer_member(ext, "byteLength", -1, file, where);
  v.stride = integer_member(ext, "byteStride", -1, file, where);
  v.count = integer_member(ext, "count", -1, file, where);
  v.mode = read_mode(ext, file, where);
  v.filter = read_filter(ext, file, where);
  check_stride(v, file, where);
  uint64_t end = 0;
  const size_t size = model.buffers[buffer].data.size();
  if (!checked_add(v.offset, v.length, end) || end > size)
    throw input_error(file, pointer_join(where, "byteLength"),
                      "byteOffset + byteLength is past the end of /buffers/" + std::to_string(buffer) + " (" +
                          std::to_string(size) + " bytes)");
  return v;
}

// The most bytes a stream of v.length bytes can decode to, by the codecs' formats: the attribute
// codec spends at least 2 bits on each 16 bytes (64:1), the triangle codec a byte on each triangle
// plus 17, the index codec a byte on each index plus 5 (the decoders refuse less, but only after
// the caller has allocated the whole output).
uint64_t most_decoded_bytes(const meshopt_view& v) {
  switch (v.mode) {
    case meshopt_mode::attributes:
      return v.length * 64 + 64 * uint64_t(v.stride);  // each block's tail and header
    case meshopt_mode::triangles:
      return v.length < 17 ? 0 : (v.length - 17) * 3 * v.stride;
    case meshopt_mode::indices:
      return v.length < 5 ? 0 : (v.length - 5) * v.stride;
  }
  return 0;
}

int decode(const meshopt_view& v, const unsigned char* source, std::vector<uint8_t>& out) {
  switch (v.mode) {
    case meshopt_mode::attributes:
      return meshopt_decodeVertexBuffer(out.data(), v.count, v.stride, source, v.length);
    case meshopt_mode::triangles:
      return meshopt_decodeIndexBuffer(out.data(), v.count, v.stride, source, v.length);
    case meshopt_mode::indices:
      return meshopt_decodeIndexSequence(out.data(), v.count, v.stride, source, v.length);
  }
  return -1;
}

void apply_filter(const meshopt_view& v, std::vector<uint8_t>& out) {
  switch (v.filter) {
    case meshopt_filter::none:
      return;
    case meshopt_filter::octahedral:
      return meshopt_decodeFilterOct(out.data(), v.count, v.stride);
    case meshopt_filter::quaternion:
      return meshopt_decodeFilterQuat(out.data(), v.count, v.stride);
    case meshopt_filter::exponential:
      return meshopt_decodeFilterExp(out.data(), v.count, v.stride);
  }
}

void decode_view(tinygltf::Model& model, size_t index, const std::string& file, memory_charge* memory) {
  const std::string view_where = pointer("bufferViews", int64_t(index));
  const std::string where = pointer_join(pointer_join(view_where, "extensions"), meshopt_extension);
  const meshopt_view v =
      read_extension(model, model.bufferViews[index].extensions.at(meshopt_extension), file, where);
  uint64_t size = 0;
  if (!checked_mul(v.count, v.stride, size) || size != model.bufferViews[index].byteLength)
    throw input_error(file, where,
                      "count " + std::to_string(v.count) + " x byteStride " + std::to_string(v.stride) +
                          " does not equal the bufferView's byteLength " +
                          std::to_string(model.bufferViews[index].byteLength));
  if (const uint64_t most = most_decoded_bytes(v); size > most)
    throw input_error(file, where,
                      "count " + std::to_string(v.count) + " x byteStride " + std::to_string(v.stride) +
                          " is " + std::to_string(size) + " bytes, more than the " +
                          std::to_string(v.length) + "-byte meshopt stream can decode to (at most " +
                          std::to_string(most) + ")");
  if (memory) memory->add(size, file, "decoded meshopt data");
  std::vector<uint8_t> out(static_cast<size_t>(size));
  const unsigned char* source = model.buffers[static_cast<size_t>(v.buffer)].data.data() + v.offset;
  if (const int rc = decode(v, source, out); rc != 0)
    throw input_error(file, where,
                      "corrupt meshopt stream (the decoder returned " + std::to_string(rc) + ")");
  apply_filter(v, out);
  tinygltf::Buffer decoded;
  decoded.data = std::move(out);
  model.buffers.push_back(std::move(decoded));
  tinygltf::BufferView& view = model.bufferViews[index];
  view.buffer = static_cast<int>(model.buffers.size() - 1);
  view.byteOffset = 0;
}

}  // namespace

bool fill_meshopt_fallback_buffers(json& doc) {
  auto buffers = doc.find("buffers");
  if (buffers == doc.end() || !buffers->is_array()) return false;
  bool changed = false;
  for (json& buffer : *buffers) {
    if (!buffer.is_object() || (buffer.contains("uri") && buffer["uri"].is_string())) continue;
    const json* ext = buffer.contains("extensions") && buffer["extensions"].is_object() &&
                              buffer["extensions"].contains(meshopt_extension)
                          ? &buffer["extensions"][meshopt_extension]
                          : nullptr;
    if (!ext || !ext->is_object() || ext->value("fallback", false) != true) continue;
    buffer["uri"] = placeholder_uri;
    buffer["byteLength"] = uint64_t{4};
    changed = true;
  }
  return changed;
}

void decode_meshopt_views(tinygltf::Model& model, const std::string& file, memory_charge* memory) {
  // Placeholder bytes must never be read as data: a fallback buffer that came with a real uri
  // keeps what it read.
  std::vector<bool> fallback(model.buffers.size(), false);
  for (size_t b = 0; b < model.buffers.size(); ++b) {
    fallback[b] = is_fallback(model.buffers[b]);
    if (fallback[b] && model.buffers[b].uri == placeholder_uri) model.buffers[b].data.clear();
  }
  const size_t view_count = model.bufferViews.size();
  for (size_t i = 0; i < view_count; ++i) {
    if (model.bufferViews[i].extensions.count(meshopt_extension) > 0) {
      decode_view(model, i, file, memory);
      continue;
    }
    const int buffer = model.bufferViews[i].buffer;
    if (buffer >= 0 && static_cast<size_t>(buffer) < fallback.size() &&
        fallback[static_cast<size_t>(buffer)] && model.buffers[static_cast<size_t>(buffer)].data.empty())
      throw input_error(
          file, pointer_join(pointer("bufferViews", int64_t(i)), "buffer"),
          "reads /buffers/" + std::to_string(buffer) +
              ", a meshopt fallback buffer without data (only compressed bufferViews may name it)");
  }
}

}  // namespace kiln::gltf_internal
