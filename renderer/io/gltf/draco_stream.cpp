#include "io/gltf/draco_stream.h"

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

#include <cstring>
#include <memory>
#include <string>

#include "io/gltf/draco_header.h"

namespace kiln::gltf_internal {
namespace {

size_t glTF_component_size(int component_type) {
  switch (component_type) {
    case 5120:
    case 5121:
      return 1;
    case 5122:
    case 5123:
      return 2;
    case 5125:
    case 5126:
      return 4;
    default:
      return 0;
  }
}

// Every point's value converted to T by the decoder (which also maps normalised integers).
template <typename T>
bool convert_all(const draco::PointCloud& cloud, const draco::PointAttribute& attribute, size_t components,
                 std::vector<uint8_t>& out) {
  const size_t points = cloud.num_points();
  out.resize(points * components * sizeof(T));
  std::vector<T> value(components);
  for (draco::PointIndex i(0); i < static_cast<uint32_t>(points); ++i) {
    const draco::AttributeValueIndex v = attribute.mapped_index(i);
    if (v.value() >= attribute.size()) return false;
    if (!attribute.ConvertValue<T>(v, static_cast<int8_t>(components), value.data())) return false;
    std::memcpy(out.data() + i.value() * components * sizeof(T), value.data(), components * sizeof(T));
  }
  return true;
}

bool convert_attribute(const draco::PointCloud& cloud, const draco::PointAttribute& attribute,
                       const draco_attribute_want& want, std::vector<uint8_t>& out) {
  switch (want.component_type) {
    case 5120:
      return convert_all<int8_t>(cloud, attribute, want.components, out);
    case 5121:
      return convert_all<uint8_t>(cloud, attribute, want.components, out);
    case 5122:
      return convert_all<int16_t>(cloud, attribute, want.components, out);
    case 5123:
      return convert_all<uint16_t>(cloud, attribute, want.components, out);
    case 5125:
      return convert_all<uint32_t>(cloud, attribute, want.components, out);
    case 5126:
      return convert_all<float>(cloud, attribute, want.components, out);
    default:
      return false;
  }
}

// The triangles of a mesh as uint32 indices, each checked against the point count.
bool mesh_indices(const draco::Mesh& mesh, std::vector<uint32_t>& out, std::string& problem) {
  const uint32_t points = mesh.num_points();
  out.resize(static_cast<size_t>(mesh.num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh.face(f);
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t index = face[k].value();
      if (index >= points) {
        problem = "triangle " + std::to_string(f.value()) + " names point " + std::to_string(index) + " of " +
                  std::to_string(points);
        return false;
      }
      out[f.value() * 3 + k] = index;
    }
  }
  return true;
}

}  // namespace

std::optional<draco_geometry> decode_draco_stream(const uint8_t* data, size_t size,
                                                  const std::vector<draco_attribute_want>& wants,
                                                  const draco_stream_limits& limits, std::string& problem) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) {
    problem = type.status().error_msg_string();
    return std::nullopt;
  }
  // Only triangle meshes: kiln renders no points, and a point cloud's header alone makes the
  // decoder allocate per declared point (fuzz_draco_stream: 266 bytes asked for gigabytes).
  if (type.value() != draco::TRIANGULAR_MESH) {
    problem = "the stream is a point cloud, not a triangle mesh";
    return std::nullopt;
  }
  if (const auto declared = read_draco_declared_counts(data, size)) {
    // glTF maps attributes by id and never reads Draco metadata; past it the counts the decoder
    // allocates by cannot be checked (fuzz_draco_stream: 4.4 GB asked for behind a metadata flag).
    if (declared->metadata) {
      problem = "the stream carries Draco metadata, which kiln does not read";
      return std::nullopt;
    }
    if (declared->faces > limits.max_faces || declared->vertices > limits.max_points) {
      problem = "the stream declares " + std::to_string(declared->faces) + " faces and " +
                std::to_string(declared->vertices) + " vertices, more than its accessors hold (" +
                std::to_string(limits.max_faces) + " faces, " + std::to_string(limits.max_points) +
                " points)";
      return std::nullopt;
    }
  }
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) {
    problem = decoded.status().error_msg_string();
    return std::nullopt;
  }
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  const draco::PointCloud* cloud = mesh.get();
  draco_geometry out;
  out.point_count = cloud->num_points();
  out.is_mesh = true;
  if (!mesh_indices(*mesh, out.indices, problem)) return std::nullopt;
  for (const draco_attribute_want& want : wants) {
    const draco::PointAttribute* attribute = cloud->GetAttributeByUniqueId(want.id);
    if (attribute == nullptr) {
      problem = "the stream has no attribute with id " + std::to_string(want.id);
      return std::nullopt;
    }
    if (static_cast<size_t>(attribute->num_components()) != want.components) {
      problem = "attribute " + std::to_string(want.id) + " has " +
                std::to_string(attribute->num_components()) + " components, its accessor " +
                std::to_string(want.components);
      return std::nullopt;
    }
    // glTF has no boolean components, and reading a Draco bool that holds another byte value is
    // undefined behaviour (fuzz_draco_stream found one holding 9).
    if (attribute->data_type() == draco::DT_BOOL || attribute->data_type() == draco::DT_INVALID) {
      problem = "attribute " + std::to_string(want.id) + " has a Draco data type glTF cannot hold";
      return std::nullopt;
    }
    if (glTF_component_size(want.component_type) == 0) {
      problem = "componentType " + std::to_string(want.component_type) + " cannot hold a Draco attribute";
      return std::nullopt;
    }
    out.attributes.emplace_back();
    if (!convert_attribute(*cloud, *attribute, want, out.attributes.back())) {
      problem = "attribute " + std::to_string(want.id) + " does not convert to its accessor's type";
      return std::nullopt;
    }
  }
  return out;
}

}  // namespace kiln::gltf_internal
