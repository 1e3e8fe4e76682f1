#include "io/gltf/gltf_draco.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <optional>
#include <utility>

#include "core/error.h"
#include "core/memory_budget.h"
#include "io/gltf/draco_stream.h"
#include "io/gltf/gltf_accessors.h"
#include "io/gltf/gltf_common.h"

namespace kiln::gltf_internal {
namespace {

using json = nlohmann::json;

// One primitive's extension object, read and range-checked.
struct draco_primitive {
  std::string where;  // /meshes/m/primitives/p/extensions/KHR_draco_mesh_compression
  int view = -1;
  std::vector<std::pair<int, draco_attribute_want>> accessors;  // accessor index, what to decode
  std::vector<std::string> names;                               // attribute names, same order
};

int int_member(const tinygltf::Value& object, const char* key) {
  if (!object.Has(key)) return -1;
  const tinygltf::Value& v = object.Get(key);
  if (!v.IsInt() && !v.IsNumber()) return -1;
  const double d = v.GetNumberAsDouble();
  return d >= 0 && d <= 2147483647.0 && d == static_cast<double>(static_cast<int>(d)) ? static_cast<int>(d)
                                                                                      : -1;
}

void check_accessor(const tinygltf::Model& model, int accessor, const std::string& file,
                    const std::string& where) {
  if (accessor < 0 || static_cast<size_t>(accessor) >= model.accessors.size())
    throw input_error(file, where,
                      "/accessors/" + std::to_string(accessor) + " does not exist (file has " +
                          std::to_string(model.accessors.size()) + " accessors)");
}

draco_primitive read_extension(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                               const std::string& where, const std::string& file) {
  const tinygltf::Value& ext = prim.extensions.at(draco_extension);
  draco_primitive out;
  out.where = where;
  if (!ext.IsObject()) throw input_error(file, where, "the extension must be an object");
  out.view = int_member(ext, "bufferView");
  if (out.view < 0 || static_cast<size_t>(out.view) >= model.bufferViews.size())
    throw input_error(file, pointer_join(where, "bufferView"),
                      "needs the index of an existing bufferView (file has " +
                          std::to_string(model.bufferViews.size()) + ")");
  const tinygltf::Value& attributes = ext.Get("attributes");
  if (!attributes.IsObject()) throw input_error(file, pointer_join(where, "attributes"), "must be an object");
  for (const std::string& name : attributes.Keys()) {
    const std::string attribute_where = pointer_join(pointer_join(where, "attributes"), name);
    const int id = int_member(attributes, name.c_str());
    if (id < 0) throw input_error(file, attribute_where, "must be a Draco attribute id (an integer >= 0)");
    auto it = prim.attributes.find(name);
    if (it == prim.attributes.end())
      throw input_error(file, attribute_where, "the primitive has no attribute " + shown(name));
    check_accessor(model, it->second, file, attribute_where);
    const tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(it->second)];
    if (component_size(acc.componentType) == 0 || component_count(acc.type) == 0)
      throw input_error(file, pointer("accessors", it->second),
                        component_type_name(acc.componentType) + " " + type_name(acc.type) +
                            " cannot hold a Draco attribute");
    out.accessors.push_back(
        {it->second, {static_cast<uint32_t>(id), acc.componentType, component_count(acc.type)}});
    out.names.push_back(name);
  }
  if (prim.indices >= 0) check_accessor(model, prim.indices, file, pointer_join(where, "indices"));
  return out;
}

// The bytes of the stream, after checking they lie inside the bufferView's buffer.
std::pair<const uint8_t*, size_t> stream_bytes(const tinygltf::Model& model, const draco_primitive& d,
                                               const std::string& file) {
  const tinygltf::BufferView& bv = model.bufferViews[static_cast<size_t>(d.view)];
  const std::string where = pointer("bufferViews", d.view);
  if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= model.buffers.size())
    throw input_error(file, pointer_join(where, "buffer"), "does not name an existing buffer");
  const std::vector<unsigned char>& data = model.buffers[static_cast<size_t>(bv.buffer)].data;
  uint64_t end = 0;
  if (!checked_add(bv.byteOffset, bv.byteLength, end) || end > data.size())
    throw input_error(file, where,
                      "byteOffset + byteLength is past the end of buffer " + std::to_string(bv.buffer) +
                          " (" + std::to_string(data.size()) + " bytes)");
  return {data.data() + bv.byteOffset, bv.byteLength};
}

// Appends bytes as a new buffer with one bufferView covering it; returns the view's index.
int append_view(tinygltf::Model& model, std::vector<uint8_t> bytes) {
  tinygltf::Buffer buffer;
  buffer.data = std::move(bytes);
  tinygltf::BufferView view;
  view.buffer = static_cast<int>(model.buffers.size());
  view.byteOffset = 0;
  view.byteLength = buffer.data.size();
  model.buffers.push_back(std::move(buffer));
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

void point_accessor_at(tinygltf::Accessor& acc, int view) {
  acc.bufferView = view;
  acc.byteOffset = 0;
}

// Which stream each accessor was decoded from: primitives sharing a stream share accessors.
using decoded_from = std::map<int, int>;

bool claim(decoded_from& done, int accessor, int view, const std::string& file, const std::string& where) {
  auto [it, inserted] = done.emplace(accessor, view);
  if (inserted) return true;
  if (it->second == view) return false;
  throw input_error(file, where,
                    "/accessors/" + std::to_string(accessor) +
                        " is also decoded from another Draco stream (/bufferViews/" +
                        std::to_string(it->second) + ")");
}

void decode_primitive(tinygltf::Model& model, tinygltf::Primitive& prim, const draco_primitive& d,
                      const std::string& file, memory_charge* memory, decoded_from& done) {
  std::vector<draco_attribute_want> wants;
  for (const auto& a : d.accessors) wants.push_back(a.second);
  const auto [bytes, size] = stream_bytes(model, d, file);
  // The accessors say what the stream decodes to; a header declaring more is refused unread.
  draco_stream_limits limits;
  limits.max_points = 0;
  for (const auto& a : d.accessors)
    limits.max_points =
        std::max<uint64_t>(limits.max_points, model.accessors[static_cast<size_t>(a.first)].count);
  if (prim.indices >= 0) limits.max_faces = model.accessors[static_cast<size_t>(prim.indices)].count / 3;
  std::string problem;
  std::optional<draco_geometry> g = decode_draco_stream(bytes, size, wants, limits, problem);
  if (!g) throw input_error(file, d.where, "corrupt Draco stream: " + shown(problem));
  for (size_t i = 0; i < d.accessors.size(); ++i) {
    const int index = d.accessors[i].first;
    const std::string where = pointer_join(pointer_join(d.where, "attributes"), d.names[i]);
    if (!claim(done, index, d.view, file, where)) continue;
    tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(index)];
    if (acc.count != g->point_count)
      throw input_error(file, where,
                        "the Draco stream decodes " + std::to_string(g->point_count) +
                            " points but /accessors/" + std::to_string(index) + " has count " +
                            std::to_string(acc.count));
    if (memory) memory->add(g->attributes[i].size(), file, "decoded Draco attributes");
    point_accessor_at(acc, append_view(model, std::move(g->attributes[i])));
  }
  if (prim.indices < 0) return;
  const std::string where = pointer_join(d.where, "indices");
  if (!g->is_mesh)
    throw input_error(file, where, "the Draco stream is a point cloud but the primitive has indices");
  if (!claim(done, prim.indices, d.view, file, where)) return;
  tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(prim.indices)];
  if (acc.count != g->indices.size())
    throw input_error(file, where,
                      "the Draco stream decodes " + std::to_string(g->indices.size()) +
                          " indices but /accessors/" + std::to_string(prim.indices) + " has count " +
                          std::to_string(acc.count));
  // Decoded indices are kept as uint32 whatever width the accessor declares: a point index
  // never has to be narrowed.
  std::vector<uint8_t> index_bytes(g->indices.size() * sizeof(uint32_t));
  std::memcpy(index_bytes.data(), g->indices.data(), index_bytes.size());
  if (memory) memory->add(index_bytes.size(), file, "decoded Draco indices");
  acc.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  acc.type = TINYGLTF_TYPE_SCALAR;
  acc.normalized = false;
  point_accessor_at(acc, append_view(model, std::move(index_bytes)));
}

}  // namespace

bool lend_draco_index_views(json& doc, const std::string& file) {
  auto meshes = doc.find("meshes");
  auto accessors = doc.find("accessors");
  if (meshes == doc.end() || !meshes->is_array() || accessors == doc.end() || !accessors->is_array())
    return false;
  auto views = doc.find("bufferViews");
  const size_t view_count = views != doc.end() && views->is_array() ? views->size() : 0;
  bool changed = false;
  for (size_t m = 0; m < meshes->size(); ++m) {
    json& mesh = (*meshes)[m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
      json& prim = mesh["primitives"][p];
      if (!prim.is_object() || !prim.contains("indices") || !prim["indices"].is_number_unsigned()) continue;
      if (!prim.contains("extensions") || !prim["extensions"].is_object() ||
          !prim["extensions"].contains(draco_extension))
        continue;
      const size_t index = prim["indices"].get<size_t>();
      if (index >= accessors->size() || !(*accessors)[index].is_object() ||
          (*accessors)[index].contains("bufferView"))
        continue;
      const json& ext = prim["extensions"][draco_extension];
      const json* view = ext.is_object() && ext.contains("bufferView") ? &ext["bufferView"] : nullptr;
      if (!view || !view->is_number_unsigned() || view->get<uint64_t>() >= view_count)
        throw input_error(
            file,
            pointer_join(
                pointer_join(
                    pointer_join(
                        pointer_join(pointer_join(pointer("meshes", int64_t(m)), "primitives"), int64_t(p)),
                        "extensions"),
                    draco_extension),
                "bufferView"),
            "needs the index of an existing bufferView (file has " + std::to_string(view_count) + ")");
      (*accessors)[index]["bufferView"] = *view;
      changed = true;
    }
  }
  return changed;
}

void decode_draco_primitives(tinygltf::Model& model, const std::string& file, memory_charge* memory) {
  decoded_from done;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& prim = model.meshes[m].primitives[p];
      if (prim.extensions.count(draco_extension) == 0) continue;
      const std::string where = pointer_join(
          pointer_join(pointer_join(pointer_join(pointer("meshes", int64_t(m)), "primitives"), int64_t(p)),
                       "extensions"),
          draco_extension);
      const draco_primitive d = read_extension(model, prim, where, file);
      decode_primitive(model, prim, d, file, memory, done);
    }
  }
}

}  // namespace kiln::gltf_internal
