#include "io/gltf/gltf_validate.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/error.h"
#include "core/format_number.h"
#include "core/message_text.h"
#include "io/gltf/gltf_accessors.h"
#include "io/gltf/gltf_common.h"
#include "io/gltf/gltf_loader.h"

namespace kiln::gltf_internal {
namespace {

// Checks an index reference. -1 means "absent" for optional references; anything else must
// name an existing element of a collection of `size` elements.
void check_ref(int value, size_t size, bool optional, const char* collection, const std::string& file,
               const std::string& where) {
  if (optional && value == -1) return;
  if (value < 0 || static_cast<size_t>(value) >= size)
    throw input_error(file, where,
                      "/" + std::string(collection) + "/" + std::to_string(value) +
                          " does not exist (file has " + std::to_string(size) + " " + collection + ")");
}

// ---- buffers and bufferViews ---------------------------------------------------------------

void validate_buffer_views(const tinygltf::Model& model, const std::string& file) {
  for (size_t v = 0; v < model.bufferViews.size(); ++v) {
    const tinygltf::BufferView& bv = model.bufferViews[v];
    const std::string where = pointer("bufferViews", static_cast<int64_t>(v));
    check_ref(bv.buffer, model.buffers.size(), false, "buffers", file, pointer_join(where, "buffer"));
    const size_t available = model.buffers[static_cast<size_t>(bv.buffer)].data.size();
    if (bv.byteLength == 0)
      throw input_error(file, pointer_join(where, "byteLength"), "byteLength must be at least 1");
    uint64_t end = 0;
    if (!checked_add(bv.byteOffset, bv.byteLength, end) || end > available)
      throw input_error(file, where,
                        "bufferView reads past the end of buffer " + std::to_string(bv.buffer) + " (needs " +
                            (end != 0 ? std::to_string(end) : std::string("more than 2^64")) +
                            " bytes, has " + std::to_string(available) + ")");
    if (bv.byteStride != 0) {
      if (bv.byteStride < 4 || bv.byteStride > 252 || bv.byteStride % 4 != 0)
        throw input_error(
            file, pointer_join(where, "byteStride"),
            "byteStride " + std::to_string(bv.byteStride) + " is not a multiple of 4 in 4..252");
      if (bv.byteStride > bv.byteLength)
        throw input_error(file, pointer_join(where, "byteStride"),
                          "byteStride " + std::to_string(bv.byteStride) + " is larger than byteLength " +
                              std::to_string(bv.byteLength));
    }
  }
}

// ---- accessors -------------------------------------------------------------------------------

bool is_accessor_component_type(int t) {
  return component_size(t) != 0;  // 5124 (INT) and 5130 (DOUBLE) are not glTF 2.0 accessor types
}

// Checks that `count` tightly packed elements of `elem` bytes starting at `offset` fit in `view`.
void check_fits_view(const tinygltf::Model& model, int view, uint64_t offset, uint64_t count, uint64_t stride,
                     uint64_t elem, const std::string& file, const std::string& where,
                     const std::string& what) {
  const tinygltf::BufferView& bv = model.bufferViews[static_cast<size_t>(view)];
  uint64_t span = 0;
  uint64_t needed = 0;
  const bool fits = checked_mul(count - 1, stride, span) && checked_add(span, elem, span) &&
                    checked_add(offset, span, needed) && needed <= bv.byteLength;
  if (!fits)
    throw input_error(file, where,
                      what + " reads past the end of bufferView " + std::to_string(view) + " (needs " +
                          (needed != 0 ? std::to_string(needed) : std::string("more than 2^64")) +
                          " bytes, has " + std::to_string(bv.byteLength) + ")");
}

void validate_sparse(const tinygltf::Model& model, const tinygltf::Accessor& acc, size_t elem,
                     const std::string& file, const std::string& where) {
  const std::string sparse = pointer_join(where, "sparse");
  if (acc.sparse.count < 1 || static_cast<uint64_t>(acc.sparse.count) > acc.count)
    throw input_error(
        file, pointer_join(sparse, "count"),
        "sparse count " + std::to_string(acc.sparse.count) + " is outside 1.." + std::to_string(acc.count));
  const uint64_t count = static_cast<uint64_t>(acc.sparse.count);

  const std::string indices = pointer_join(sparse, "indices");
  check_ref(acc.sparse.indices.bufferView, model.bufferViews.size(), false, "bufferViews", file,
            pointer_join(indices, "bufferView"));
  const int index_type = acc.sparse.indices.componentType;
  if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    throw input_error(file, pointer_join(indices, "componentType"),
                      "sparse indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT (got " +
                          component_type_name(index_type) + ")");
  if (acc.sparse.indices.byteOffset < 0)
    throw input_error(file, pointer_join(indices, "byteOffset"), "byteOffset must not be negative");
  const size_t index_size = component_size(index_type);
  check_fits_view(model, acc.sparse.indices.bufferView, static_cast<uint64_t>(acc.sparse.indices.byteOffset),
                  count, index_size, index_size, file, indices, "sparse indices");

  const std::string values = pointer_join(sparse, "values");
  check_ref(acc.sparse.values.bufferView, model.bufferViews.size(), false, "bufferViews", file,
            pointer_join(values, "bufferView"));
  if (acc.sparse.values.byteOffset < 0)
    throw input_error(file, pointer_join(values, "byteOffset"), "byteOffset must not be negative");
  check_fits_view(model, acc.sparse.values.bufferView, static_cast<uint64_t>(acc.sparse.values.byteOffset),
                  count, elem, elem, file, values, "sparse values");
}

void validate_accessors(const tinygltf::Model& model, const std::string& file) {
  for (size_t a = 0; a < model.accessors.size(); ++a) {
    const tinygltf::Accessor& acc = model.accessors[a];
    const std::string where = pointer("accessors", static_cast<int64_t>(a));
    if (!is_accessor_component_type(acc.componentType))
      throw input_error(file, pointer_join(where, "componentType"),
                        component_type_name(acc.componentType) + " is not a valid accessor componentType");
    if (component_count(acc.type) == 0)
      throw input_error(file, pointer_join(where, "type"),
                        type_name(acc.type) + " is not a valid accessor type");
    if (acc.count < 1) throw input_error(file, pointer_join(where, "count"), "count must be at least 1");
    if (acc.normalized && (acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                           acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
      throw input_error(file, pointer_join(where, "normalized"),
                        "normalized is not allowed for " + component_type_name(acc.componentType));
    const size_t comp = component_size(acc.componentType);
    const size_t elem = element_size(acc.componentType, acc.type);
    // An accessor without a bufferView is materialised as zeros: bound it like stored data.
    uint64_t total = 0;
    if (!checked_mul(acc.count, elem, total) || total > max_gltf_file_bytes)
      throw input_error(file, pointer_join(where, "count"),
                        "count " + std::to_string(acc.count) + " is larger than any glTF buffer can hold");

    if (acc.bufferView != -1) {
      check_ref(acc.bufferView, model.bufferViews.size(), false, "bufferViews", file,
                pointer_join(where, "bufferView"));
      const tinygltf::BufferView& bv = model.bufferViews[static_cast<size_t>(acc.bufferView)];
      if (acc.byteOffset % comp != 0)
        throw input_error(file, pointer_join(where, "byteOffset"),
                          "byteOffset " + std::to_string(acc.byteOffset) +
                              " is not a multiple of the component size " + std::to_string(comp));
      if ((bv.byteOffset + acc.byteOffset) % comp != 0)
        throw input_error(file, pointer_join(where, "byteOffset"),
                          "bufferView offset + accessor offset (" +
                              std::to_string(bv.byteOffset + acc.byteOffset) +
                              ") is not a multiple of the component size " + std::to_string(comp));
      const size_t stride = bv.byteStride != 0 ? bv.byteStride : elem;
      if (stride < elem)
        throw input_error(file, where,
                          "byteStride " + std::to_string(stride) + " of bufferView " +
                              std::to_string(acc.bufferView) + " is smaller than one " + type_name(acc.type) +
                              " " + component_type_name(acc.componentType) + " element (" +
                              std::to_string(elem) + " bytes)");
      check_fits_view(model, acc.bufferView, acc.byteOffset, acc.count, stride, elem, file, where,
                      "accessor");
    } else if (acc.byteOffset != 0) {
      throw input_error(file, pointer_join(where, "byteOffset"), "byteOffset without a bufferView");
    }
    if (acc.sparse.isSparse) validate_sparse(model, acc, elem, file, where);
  }
}

// ---- images, samplers, textures, materials ------------------------------------------------------

bool is_wrap(int v) { return v == 10497 || v == 33071 || v == 33648; }

void validate_textures(const tinygltf::Model& model, const std::string& file) {
  for (size_t i = 0; i < model.images.size(); ++i) {
    const tinygltf::Image& img = model.images[i];
    const std::string where = pointer("images", static_cast<int64_t>(i));
    // An image without bytes is refused where a material samples it (resolve_image): the
    // bytes of images nothing samples are never read.
    if (img.bufferView != -1)
      check_ref(img.bufferView, model.bufferViews.size(), false, "bufferViews", file,
                pointer_join(where, "bufferView"));
  }
  for (size_t i = 0; i < model.samplers.size(); ++i) {
    const tinygltf::Sampler& s = model.samplers[i];
    const std::string where = pointer("samplers", static_cast<int64_t>(i));
    if (!is_wrap(s.wrapS))
      throw input_error(file, pointer_join(where, "wrapS"), "unknown wrap mode " + std::to_string(s.wrapS));
    if (!is_wrap(s.wrapT))
      throw input_error(file, pointer_join(where, "wrapT"), "unknown wrap mode " + std::to_string(s.wrapT));
    if (s.magFilter != -1 && s.magFilter != 9728 && s.magFilter != 9729)
      throw input_error(file, pointer_join(where, "magFilter"),
                        "unknown magFilter " + std::to_string(s.magFilter));
    const bool known_min = s.minFilter == -1 || s.minFilter == 9728 || s.minFilter == 9729 ||
                           (s.minFilter >= 9984 && s.minFilter <= 9987);
    if (!known_min)
      throw input_error(file, pointer_join(where, "minFilter"),
                        "unknown minFilter " + std::to_string(s.minFilter));
  }
  for (size_t i = 0; i < model.textures.size(); ++i) {
    const tinygltf::Texture& t = model.textures[i];
    const std::string where = pointer("textures", static_cast<int64_t>(i));
    check_ref(t.source, model.images.size(), true, "images", file, pointer_join(where, "source"));
    check_ref(t.sampler, model.samplers.size(), true, "samplers", file, pointer_join(where, "sampler"));
  }
}

void check_texture_info(int index, int texcoord, const tinygltf::Model& model, const std::string& file,
                        const std::string& where) {
  if (index == -1) return;
  check_ref(index, model.textures.size(), false, "textures", file, pointer_join(where, "index"));
  if (texcoord < 0) throw input_error(file, pointer_join(where, "texCoord"), "texCoord must not be negative");
}

void validate_materials(const tinygltf::Model& model, const std::string& file) {
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const tinygltf::Material& m = model.materials[i];
    const std::string where = pointer("materials", static_cast<int64_t>(i));
    const std::string pbr = pointer_join(where, "pbrMetallicRoughness");
    check_texture_info(m.pbrMetallicRoughness.baseColorTexture.index,
                       m.pbrMetallicRoughness.baseColorTexture.texCoord, model, file,
                       pointer_join(pbr, "baseColorTexture"));
    check_texture_info(m.pbrMetallicRoughness.metallicRoughnessTexture.index,
                       m.pbrMetallicRoughness.metallicRoughnessTexture.texCoord, model, file,
                       pointer_join(pbr, "metallicRoughnessTexture"));
    check_texture_info(m.normalTexture.index, m.normalTexture.texCoord, model, file,
                       pointer_join(where, "normalTexture"));
    check_texture_info(m.occlusionTexture.index, m.occlusionTexture.texCoord, model, file,
                       pointer_join(where, "occlusionTexture"));
    check_texture_info(m.emissiveTexture.index, m.emissiveTexture.texCoord, model, file,
                       pointer_join(where, "emissiveTexture"));
  }
}

// ---- meshes --------------------------------------------------------------------------------

bool is_integer_8_16(int ct) {
  return ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         ct == TINYGLTF_COMPONENT_TYPE_SHORT || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
}

bool is_signed_normalized_8_16(const tinygltf::Accessor& acc) {
  return acc.normalized && (acc.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                            acc.componentType == TINYGLTF_COMPONENT_TYPE_SHORT);
}

// glTF 2.0's attribute formats; with KHR_mesh_quantization (`quantized`) also its integer ones:
// POSITION any 8/16-bit type, normalized or not; NORMAL and TANGENT normalized BYTE/SHORT;
// TEXCOORD any 8/16-bit type, normalized or not. The decoder turns all of them into floats.
void check_attribute_format(const tinygltf::Accessor& acc, const std::string& name, bool quantized,
                            const std::string& file, const std::string& where) {
  const int ct = acc.componentType;
  const bool is_float = ct == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const auto got = " (got " + type_name(acc.type) + " " + component_type_name(ct) +
                   (acc.normalized ? " normalized" : "") + ")";
  const std::string hint = quantized || is_float ? "" : "; integer formats need KHR_mesh_quantization";
  if (name == "TANGENT" || name == "NORMAL") {
    const bool tangent = name == "TANGENT";
    if (acc.type != (tangent ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3) ||
        !(is_float || (quantized && is_signed_normalized_8_16(acc))))
      throw input_error(file, where,
                        name + (tangent ? " must be VEC4 FLOAT" : " must be VEC3 FLOAT") +
                            (quantized ? " or normalized BYTE/SHORT" : "") + got + hint);
  } else if (name == "POSITION") {
    if (acc.type != TINYGLTF_TYPE_VEC3 || !(is_float || (quantized && is_integer_8_16(ct))))
      throw input_error(file, where,
                        std::string("POSITION must be VEC3 FLOAT") +
                            (quantized ? ", BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT" : "") + got + hint);
  } else if (name == "TEXCOORD_0" || name == "TEXCOORD_1") {
    const bool ok = acc.type == TINYGLTF_TYPE_VEC2 &&
                    (is_float ||
                     (acc.normalized && (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                         ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)) ||
                     (quantized && is_integer_8_16(ct)));
    if (!ok)
      throw input_error(file, where,
                        name +
                            (quantized ? " must be VEC2 FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT"
                                       : " must be VEC2 FLOAT or normalized UNSIGNED_BYTE/SHORT") +
                            got);
  } else if (name == "COLOR_0") {
    const bool ok = (acc.type == TINYGLTF_TYPE_VEC3 || acc.type == TINYGLTF_TYPE_VEC4) &&
                    (ct == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                     (acc.normalized && (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                         ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)));
    if (!ok)
      throw input_error(file, where,
                        "COLOR_0 must be VEC3/VEC4 FLOAT or normalized UNSIGNED_BYTE/SHORT" + got);
  }
}

void validate_meshes(const tinygltf::Model& model, const std::string& file) {
  const bool quantized = uses_extension(model, quantization_extension);
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const tinygltf::Mesh& mesh = model.meshes[m];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      const std::string where = pointer_join(
          pointer_join(pointer("meshes", static_cast<int64_t>(m)), "primitives"), static_cast<int64_t>(p));
      if (prim.mode < TINYGLTF_MODE_POINTS || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
        throw input_error(file, pointer_join(where, "mode"),
                          "unknown primitive mode " + std::to_string(prim.mode));
      check_ref(prim.material, model.materials.size(), true, "materials", file,
                pointer_join(where, "material"));
      const std::string attributes = pointer_join(where, "attributes");
      auto position = prim.attributes.find("POSITION");
      if (position == prim.attributes.end())
        throw input_error(file, attributes, "primitive has no POSITION attribute");
      // POSITION sets the vertex count; check its reference first, since attributes are visited
      // in name order and NORMAL comes before it.
      check_ref(position->second, model.accessors.size(), false, "accessors", file,
                pointer_join(attributes, "POSITION"));
      const size_t vertex_count = model.accessors[static_cast<size_t>(position->second)].count;
      for (const auto& [name, index] : prim.attributes) {
        check_ref(index, model.accessors.size(), false, "accessors", file, pointer_join(attributes, name));
        const tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(index)];
        check_attribute_format(acc, name, quantized, file, pointer_join(attributes, name));
        if (acc.count != vertex_count)
          throw input_error(file, pointer_join(attributes, name),
                            "accessor has " + std::to_string(acc.count) + " elements but POSITION has " +
                                std::to_string(vertex_count));
      }
      if (prim.indices != -1) {
        check_ref(prim.indices, model.accessors.size(), false, "accessors", file,
                  pointer_join(where, "indices"));
        const tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(prim.indices)];
        const int ct = acc.componentType;
        if (acc.type != TINYGLTF_TYPE_SCALAR || acc.normalized ||
            (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
             ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
          throw input_error(file, pointer_join(where, "indices"),
                            "indices must be SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT (got " +
                                type_name(acc.type) + " " + component_type_name(ct) + ")");
      }
      for (size_t t = 0; t < prim.targets.size(); ++t)
        for (const auto& [name, index] : prim.targets[t])
          check_ref(
              index, model.accessors.size(), false, "accessors", file,
              pointer_join(pointer_join(pointer_join(where, "targets"), static_cast<int64_t>(t)), name));
    }
  }
}

// ---- nodes and scenes -----------------------------------------------------------------------

bool all_finite(const std::vector<double>& values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

void check_transform_array(const std::vector<double>& values, size_t expected, const char* key,
                           const std::string& file, const std::string& where) {
  if (values.empty()) return;
  if (values.size() != expected)
    throw input_error(file, pointer_join(where, key),
                      std::string(key) + " has " + std::to_string(values.size()) + " numbers, expected " +
                          std::to_string(expected));
  if (!all_finite(values))
    throw input_error(file, pointer_join(where, key), std::string(key) + " contains NaN or infinity");
}

// glTF node matrices are TRS compositions, so their last row is 0, 0, 0, 1; kiln's transforms
// (and Embree's) are affine and would drop any other row without a word.
void check_affine(const std::vector<double>& m, const std::string& file, const std::string& where) {
  if (m.size() != 16 || (m[3] == 0.0 && m[7] == 0.0 && m[11] == 0.0 && m[15] == 1.0)) return;
  throw input_error(file, pointer_join(where, "matrix"),
                    "the last row must be 0, 0, 0, 1 (a node matrix is affine), got " + format_number(m[3]) +
                        ", " + format_number(m[7]) + ", " + format_number(m[11]) + ", " +
                        format_number(m[15]));
}

void validate_nodes(const tinygltf::Model& model, const std::string& file) {
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const tinygltf::Node& node = model.nodes[n];
    const std::string where = pointer("nodes", static_cast<int64_t>(n));
    check_ref(node.mesh, model.meshes.size(), true, "meshes", file, pointer_join(where, "mesh"));
    check_ref(node.camera, model.cameras.size(), true, "cameras", file, pointer_join(where, "camera"));
    check_ref(node.skin, model.skins.size(), true, "skins", file, pointer_join(where, "skin"));
    for (size_t c = 0; c < node.children.size(); ++c)
      check_ref(node.children[c], model.nodes.size(), false, "nodes", file,
                pointer_join(pointer_join(where, "children"), static_cast<int64_t>(c)));
    check_transform_array(node.matrix, 16, "matrix", file, where);
    check_affine(node.matrix, file, where);
    check_transform_array(node.translation, 3, "translation", file, where);
    check_transform_array(node.rotation, 4, "rotation", file, where);
    check_transform_array(node.scale, 3, "scale", file, where);
    if (!node.rotation.empty()) {
      const auto& q = node.rotation;
      if (q[0] == 0.0 && q[1] == 0.0 && q[2] == 0.0 && q[3] == 0.0)  // not its square: 1e-170 is no zero
        throw input_error(file, pointer_join(where, "rotation"), "rotation quaternion has zero length");
    }
    auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext != node.extensions.end()) {
      const std::string light_where = pointer_join(pointer_join(where, "extensions"), "KHR_lights_punctual");
      const tinygltf::Value& value = ext->second;
      if (!value.IsObject() || !value.Has("light") || !value.Get("light").IsInt())
        throw input_error(file, light_where, "expected an object with an integer 'light'");
      check_ref(value.Get("light").GetNumberAsInt(), model.lights.size(), false, "lights", file,
                pointer_join(light_where, "light"));
    }
  }
}

// With at most one parent per node, the graph is a forest plus, possibly, cycles that no root
// reaches; one iterative walk from the roots visits every node that is not on or under a cycle.
void validate_node_graph(const tinygltf::Model& model, const std::string& file) {
  const size_t count = model.nodes.size();
  std::vector<int> parent(count, -1);
  for (size_t n = 0; n < count; ++n) {
    for (size_t c = 0; c < model.nodes[n].children.size(); ++c) {
      const size_t child = static_cast<size_t>(model.nodes[n].children[c]);
      const std::string where = pointer_join(
          pointer_join(pointer("nodes", static_cast<int64_t>(n)), "children"), static_cast<int64_t>(c));
      if (child == n) throw input_error(file, where, "node is its own child (node graph has a cycle)");
      if (parent[child] != -1)
        throw input_error(file, where,
                          "node " + std::to_string(child) + " already has parent node " +
                              std::to_string(parent[child]) + " (a node may have only one parent)");
      parent[child] = static_cast<int>(n);
    }
  }
  std::vector<char> reached(count, 0);
  std::vector<size_t> stack;
  for (size_t n = 0; n < count; ++n)
    if (parent[n] == -1) stack.push_back(n);
  size_t visits = 0;
  while (!stack.empty()) {
    const size_t n = stack.back();
    stack.pop_back();
    if (reached[n] || ++visits > count) break;  // cannot happen in a forest; bounds the walk anyway
    reached[n] = 1;
    for (int child : model.nodes[n].children) stack.push_back(static_cast<size_t>(child));
  }
  for (size_t n = 0; n < count; ++n)
    if (!reached[n])
      throw input_error(file, pointer("nodes", static_cast<int64_t>(n)),
                        "node is part of a cycle in the node graph");

  for (size_t s = 0; s < model.scenes.size(); ++s) {
    const auto& roots = model.scenes[s].nodes;
    const std::string where = pointer_join(pointer("scenes", static_cast<int64_t>(s)), "nodes");
    for (size_t i = 0; i < roots.size(); ++i) {
      check_ref(roots[i], count, false, "nodes", file, pointer_join(where, static_cast<int64_t>(i)));
      const int p = parent[static_cast<size_t>(roots[i])];
      if (p != -1)
        throw input_error(file, pointer_join(where, static_cast<int64_t>(i)),
                          "node " + std::to_string(roots[i]) + " is not a root node (its parent is node " +
                              std::to_string(p) + ")");
    }
  }
  if (model.defaultScene != -1)
    check_ref(model.defaultScene, model.scenes.size(), false, "scenes", file, "/scene");
}

// ---- cameras, lights, skins, animations ------------------------------------------------------

void validate_cameras(const tinygltf::Model& model, const std::string& file) {
  const double pi_d = 3.14159265358979323846;
  for (size_t c = 0; c < model.cameras.size(); ++c) {
    const tinygltf::Camera& cam = model.cameras[c];
    const std::string where = pointer("cameras", static_cast<int64_t>(c));
    if (cam.type == "perspective") {
      const auto& p = cam.perspective;
      const std::string at = pointer_join(where, "perspective");
      if (!all_finite({p.yfov, p.znear, p.zfar, p.aspectRatio}))
        throw input_error(file, at, "perspective camera has a NaN or infinite value");
      if (!(p.yfov > 0.0 && p.yfov < pi_d))
        throw input_error(file, pointer_join(at, "yfov"),
                          "yfov " + format_number(p.yfov) + " is not in (0, pi)");
      if (p.aspectRatio < 0.0)
        throw input_error(file, pointer_join(at, "aspectRatio"), "aspectRatio must be positive");
      // glTF's schema: exclusiveMinimum 0 (a perspective projection divides by znear).
      if (!(p.znear > 0.0))
        throw input_error(file, pointer_join(at, "znear"),
                          "znear must be greater than 0, got " + format_number(p.znear));
      if (p.zfar != 0.0 && p.zfar <= p.znear)
        throw input_error(file, pointer_join(at, "zfar"), "zfar must be greater than znear");
    } else if (cam.type == "orthographic") {
      const auto& o = cam.orthographic;
      const std::string at = pointer_join(where, "orthographic");
      if (!all_finite({o.xmag, o.ymag, o.znear, o.zfar}))
        throw input_error(file, at, "orthographic camera has a NaN or infinite value");
      if (o.xmag == 0.0 || o.ymag == 0.0) throw input_error(file, at, "xmag and ymag must not be zero");
      if (o.znear < 0.0) throw input_error(file, pointer_join(at, "znear"), "znear must not be negative");
      if (o.zfar <= o.znear)
        throw input_error(file, pointer_join(at, "zfar"), "zfar must be greater than znear");
    } else {
      throw input_error(file, pointer_join(where, "type"), "unknown camera type " + quoted(cam.type));
    }
  }
}

void validate_lights(const tinygltf::Model& model, const std::string& file) {
  const double half_pi = 1.57079632679489661923;
  for (size_t l = 0; l < model.lights.size(); ++l) {
    const tinygltf::Light& light = model.lights[l];
    const std::string where = "/extensions/KHR_lights_punctual/lights/" + std::to_string(l);
    if (light.type != "point" && light.type != "spot" && light.type != "directional")
      throw input_error(file, pointer_join(where, "type"), "unknown light type " + quoted(light.type));
    if (!light.color.empty() && (light.color.size() != 3 || !all_finite(light.color)))
      throw input_error(file, pointer_join(where, "color"), "color must be three finite numbers");
    if (!std::isfinite(light.intensity) || light.intensity < 0.0)
      throw input_error(file, pointer_join(where, "intensity"), "intensity must be finite and not negative");
    if (!std::isfinite(light.range) || light.range < 0.0)
      throw input_error(file, pointer_join(where, "range"), "range must be finite and positive");
    if (light.type == "spot") {
      const double inner = light.spot.innerConeAngle;
      const double outer = light.spot.outerConeAngle;
      if (!all_finite({inner, outer}) || inner < 0.0 || outer > half_pi || inner >= outer)
        throw input_error(file, pointer_join(where, "spot"),
                          "cone angles must satisfy 0 <= innerConeAngle (" + format_number(inner) +
                              ") < outerConeAngle (" + format_number(outer) + ") <= pi/2");
    }
  }
}

void validate_skins_and_animations(const tinygltf::Model& model, const std::string& file) {
  for (size_t s = 0; s < model.skins.size(); ++s) {
    const tinygltf::Skin& skin = model.skins[s];
    const std::string where = pointer("skins", static_cast<int64_t>(s));
    check_ref(skin.inverseBindMatrices, model.accessors.size(), true, "accessors", file,
              pointer_join(where, "inverseBindMatrices"));
    check_ref(skin.skeleton, model.nodes.size(), true, "nodes", file, pointer_join(where, "skeleton"));
    for (size_t j = 0; j < skin.joints.size(); ++j)
      check_ref(skin.joints[j], model.nodes.size(), false, "nodes", file,
                pointer_join(pointer_join(where, "joints"), static_cast<int64_t>(j)));
  }
  for (size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& anim = model.animations[a];
    const std::string where = pointer("animations", static_cast<int64_t>(a));
    for (size_t s = 0; s < anim.samplers.size(); ++s) {
      const std::string at = pointer_join(pointer_join(where, "samplers"), static_cast<int64_t>(s));
      check_ref(anim.samplers[s].input, model.accessors.size(), false, "accessors", file,
                pointer_join(at, "input"));
      check_ref(anim.samplers[s].output, model.accessors.size(), false, "accessors", file,
                pointer_join(at, "output"));
    }
    for (size_t c = 0; c < anim.channels.size(); ++c) {
      const std::string at = pointer_join(pointer_join(where, "channels"), static_cast<int64_t>(c));
      check_ref(anim.channels[c].sampler, anim.samplers.size(), false, "samplers", file,
                pointer_join(at, "sampler"));
      check_ref(anim.channels[c].target_node, model.nodes.size(), true, "nodes", file,
                pointer_join(pointer_join(at, "target"), "node"));
    }
  }
}

}  // namespace

void validate_model(const tinygltf::Model& model, const std::string& file) {
  validate_buffer_views(model, file);
  validate_accessors(model, file);
  validate_textures(model, file);
  validate_materials(model, file);
  validate_meshes(model, file);
  validate_nodes(model, file);
  validate_node_graph(model, file);
  validate_cameras(model, file);
  validate_lights(model, file);
  validate_skins_and_animations(model, file);
}

bool uses_extension(const tinygltf::Model& model, const std::string& name) {
  return std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), name) !=
         model.extensionsUsed.end();
}

int node_light_index(const tinygltf::Node& node) {
  auto ext = node.extensions.find("KHR_lights_punctual");
  if (ext == node.extensions.end() || !ext->second.IsObject() || !ext->second.Has("light")) return -1;
  const tinygltf::Value& light = ext->second.Get("light");
  return light.IsInt() ? light.GetNumberAsInt() : -1;
}

}  // namespace kiln::gltf_internal
