#include "io/gltf/gltf_accessors.h"

#include <algorithm>
#include <cstring>

#include "core/check.h"
#include "core/error.h"
#include "io/gltf/gltf_common.h"

namespace kiln::gltf_internal {
namespace {

// Rows of one matrix column (or the whole vector for non-matrix types).
size_t rows_per_column(int type) {
  switch (type) {
    case TINYGLTF_TYPE_MAT2:
      return 2;
    case TINYGLTF_TYPE_MAT3:
      return 3;
    case TINYGLTF_TYPE_MAT4:
      return 4;
    default:
      return component_count(type);
  }
}

// Byte offset of component j inside one element, honouring matrix column padding.
size_t component_offset(int component_type, int type, size_t j) {
  const size_t size = component_size(component_type);
  const size_t rows = rows_per_column(type);
  const size_t column_bytes = (rows * size + 3) / 4 * 4;
  const bool is_matrix =
      type == TINYGLTF_TYPE_MAT2 || type == TINYGLTF_TYPE_MAT3 || type == TINYGLTF_TYPE_MAT4;
  if (!is_matrix) return j * size;
  return (j / rows) * column_bytes + (j % rows) * size;
}

template <typename T>
T load(const uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof value);  // glTF data is little-endian and may be unaligned
  return value;
}

// One component as float, decoding normalised integers per the glTF specification.
float decode_float(const uint8_t* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float v = load<int8_t>(p);
      return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const float v = load<uint8_t>(p);
      return normalized ? v / 255.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const float v = load<int16_t>(p);
      return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const float v = load<uint16_t>(p);
      return normalized ? v / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return static_cast<float>(load<uint32_t>(p));
    default:
      KILN_CHECK(false && "component type was validated");
      return 0.0f;
  }
}

uint32_t decode_uint(const uint8_t* p, int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return load<uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return load<uint16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return load<uint32_t>(p);
    default:
      KILN_CHECK(false && "index component type was validated");
      return 0;
  }
}

// The bytes of bufferView `view` starting at `offset`, after re-checking that `needed` bytes
// from there lie inside both the bufferView and its buffer (validation already promised so).
const uint8_t* view_bytes(const tinygltf::Model& model, int view, uint64_t offset, uint64_t needed) {
  KILN_CHECK(view >= 0 && static_cast<size_t>(view) < model.bufferViews.size());
  const tinygltf::BufferView& bv = model.bufferViews[static_cast<size_t>(view)];
  KILN_CHECK(bv.buffer >= 0 && static_cast<size_t>(bv.buffer) < model.buffers.size());
  const tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(bv.buffer)];
  uint64_t end = 0;
  KILN_CHECK(checked_add(offset, needed, end) && end <= bv.byteLength);
  uint64_t buffer_end = 0;
  KILN_CHECK(checked_add(bv.byteOffset, bv.byteLength, buffer_end) && buffer_end <= buffer.data.size());
  return buffer.data.data() + bv.byteOffset + offset;
}

// Visits every element of an accessor: decode(element_index, element_bytes). Elements come from
// the base bufferView (or are zero when there is none), then sparse substitutions overwrite them.
template <typename Decode>
void for_each_element(const tinygltf::Model& model, int index, const std::string& file, Decode decode) {
  const tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(index)];
  const size_t elem = element_size(acc.componentType, acc.type);
  KILN_CHECK(elem > 0 && acc.count > 0);

  if (acc.bufferView >= 0) {
    const tinygltf::BufferView& bv = model.bufferViews[static_cast<size_t>(acc.bufferView)];
    const size_t stride = bv.byteStride != 0 ? bv.byteStride : elem;
    const uint64_t span = static_cast<uint64_t>(acc.count - 1) * stride + elem;
    const uint8_t* base = view_bytes(model, acc.bufferView, acc.byteOffset, span);
    for (size_t i = 0; i < acc.count; ++i) decode(i, base + i * stride);
  } else {
    const std::vector<uint8_t> zero(elem, 0);
    for (size_t i = 0; i < acc.count; ++i) decode(i, zero.data());
  }

  if (!acc.sparse.isSparse) return;
  const size_t sparse_count = static_cast<size_t>(acc.sparse.count);
  const int index_type = acc.sparse.indices.componentType;
  const size_t index_size = component_size(index_type);
  const uint8_t* indices =
      view_bytes(model, acc.sparse.indices.bufferView, static_cast<uint64_t>(acc.sparse.indices.byteOffset),
                 static_cast<uint64_t>(sparse_count) * index_size);
  const uint8_t* values =
      view_bytes(model, acc.sparse.values.bufferView, static_cast<uint64_t>(acc.sparse.values.byteOffset),
                 static_cast<uint64_t>(sparse_count) * elem);
  const std::string where = pointer_join(pointer_join(pointer("accessors", index), "sparse"), "indices");
  uint64_t previous = 0;
  for (size_t k = 0; k < sparse_count; ++k) {
    const uint32_t target = decode_uint(indices + k * index_size, index_type);
    if (target >= acc.count)
      throw input_error(file, where,
                        "sparse index " + std::to_string(target) + " at position " + std::to_string(k) +
                            " is out of range (accessor has " + std::to_string(acc.count) + " elements)");
    if (k > 0 && target <= previous)
      throw input_error(file, where,
                        "sparse indices must strictly increase (" + std::to_string(target) + " follows " +
                            std::to_string(previous) + ")");
    previous = target;
    decode(target, values + k * elem);
  }
}

}  // namespace

size_t component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

size_t component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

size_t element_size(int component_type, int type) {
  const size_t size = component_size(component_type);
  const size_t count = component_count(type);
  if (size == 0 || count == 0) return 0;
  const size_t rows = rows_per_column(type);
  const size_t columns = count / rows;
  if (columns == 1) return count * size;
  return columns * ((rows * size + 3) / 4 * 4);
}

std::string component_type_name(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT:
      return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "FLOAT";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE:
      return "DOUBLE";
    default:
      return "componentType " + std::to_string(component_type);
  }
}

std::string type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "type " + std::to_string(type);
  }
}

std::vector<float> read_accessor_floats(const tinygltf::Model& model, int index, const std::string& file) {
  const tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(index)];
  const size_t components = component_count(acc.type);
  std::vector<size_t> offsets(components);
  for (size_t j = 0; j < components; ++j) offsets[j] = component_offset(acc.componentType, acc.type, j);
  std::vector<float> out(acc.count * components);
  for_each_element(model, index, file, [&](size_t i, const uint8_t* element) {
    for (size_t j = 0; j < components; ++j)
      out[i * components + j] = decode_float(element + offsets[j], acc.componentType, acc.normalized);
  });
  return out;
}

std::vector<uint32_t> read_accessor_indices(const tinygltf::Model& model, int index,
                                            const std::string& file) {
  const tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(index)];
  KILN_CHECK(acc.type == TINYGLTF_TYPE_SCALAR);
  std::vector<uint32_t> out(acc.count);
  for_each_element(model, index, file, [&](size_t i, const uint8_t* element) {
    out[i] = decode_uint(element, acc.componentType);
  });
  return out;
}

}  // namespace kiln::gltf_internal
