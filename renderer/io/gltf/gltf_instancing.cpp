#include "io/gltf/gltf_instancing.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "io/gltf/gltf_accessors.h"
#include "io/gltf/gltf_common.h"

namespace kiln::gltf_internal {
namespace {

bool is_small_integer(int ct) {
  return ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         ct == TINYGLTF_COMPONENT_TYPE_SHORT || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
}

// Checks one attribute's accessor reference and format; returns the accessor index.
int check_attribute(const tinygltf::Model& model, const tinygltf::Value& value, const std::string& name,
                    bool quantized, const std::string& file, const std::string& where) {
  if (!value.IsInt()) throw input_error(file, where, name + " must be an accessor index");
  const int index = value.GetNumberAsInt();
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
    throw input_error(file, where,
                      "/accessors/" + std::to_string(index) + " does not exist (file has " +
                          std::to_string(model.accessors.size()) + " accessors)");
  const tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(index)];
  const int ct = acc.componentType;
  const bool rotation = name == "ROTATION";
  const int type = rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3;
  const bool ok =
      acc.type == type && (ct == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                           (rotation && acc.normalized &&
                            (ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT)) ||
                           (!rotation && quantized && is_small_integer(ct)));
  if (!ok) {
    const std::string allowed = rotation    ? "VEC4 FLOAT or normalized BYTE/SHORT"
                                : quantized ? "VEC3 FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT"
                                            : "VEC3 FLOAT";
    throw input_error(file, where,
                      name + " must be " + allowed + " (got " + type_name(acc.type) + " " +
                          component_type_name(ct) + (acc.normalized ? " normalized" : "") + ")");
  }
  return index;
}

// The attribute's values, count * components floats, refusing NaN and infinity.
std::vector<float> read_values(const tinygltf::Model& model, int accessor, const std::string& file,
                               const std::string& where) {
  std::vector<float> values = read_accessor_floats(model, accessor, file);
  const size_t components = component_count(model.accessors[static_cast<size_t>(accessor)].type);
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw input_error(file, where, "instance " + std::to_string(i / components) + " is NaN or infinite");
  return values;
}

}  // namespace

dvec4 unit_quaternion(const dvec4& q) {
  const double largest = std::max({std::abs(q.x), std::abs(q.y), std::abs(q.z), std::abs(q.w)});
  if (!(largest > 0.0)) return dvec4(0.0);
  const dvec4 scaled = q / largest;
  return scaled / glm::length(scaled);
}

dmat4 trs_matrix(const dvec3& translation, const dvec4& rotation, const dvec3& scale) {
  const dvec4 unit = unit_quaternion(rotation);  // callers refuse a zero quaternion
  const double x = unit.x, y = unit.y, z = unit.z, w = unit.w;
  dmat4 m(1.0);
  m[0] = dvec4(1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0) * scale.x;
  m[1] = dvec4(2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0) * scale.y;
  m[2] = dvec4(2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0) * scale.z;
  m[3] = dvec4(translation, 1.0);
  return m;
}

std::optional<std::vector<dmat4>> read_gpu_instances(const tinygltf::Model& model, int node_index,
                                                     bool quantized, const instance_budget& budget,
                                                     const std::string& file) {
  const tinygltf::Node& node = model.nodes[static_cast<size_t>(node_index)];
  auto ext = node.extensions.find(gpu_instancing_extension);
  if (ext == node.extensions.end()) return std::nullopt;
  const std::string where =
      pointer_join(pointer_join(pointer("nodes", node_index), "extensions"), gpu_instancing_extension);
  const std::string attributes_where = pointer_join(where, "attributes");
  if (!ext->second.IsObject() || !ext->second.Has("attributes") || !ext->second.Get("attributes").IsObject())
    throw input_error(file, where, "expected an object with an 'attributes' object");
  const tinygltf::Value& attributes = ext->second.Get("attributes");

  // Each attribute's accessor (-1: absent, the identity for that part), checked before any read.
  const char* names[3] = {"TRANSLATION", "ROTATION", "SCALE"};
  int accessors[3] = {-1, -1, -1};
  size_t count = 0;
  std::string first;
  for (int a = 0; a < 3; ++a) {
    if (!attributes.Has(names[a])) continue;
    const std::string at = pointer_join(attributes_where, names[a]);
    accessors[a] = check_attribute(model, attributes.Get(names[a]), names[a], quantized, file, at);
    const size_t n = model.accessors[static_cast<size_t>(accessors[a])].count;
    if (first.empty()) {
      first = names[a];
      count = n;
    } else if (n != count) {
      throw input_error(file, at,
                        std::string(names[a]) + " has " + std::to_string(n) + " instances but " + first +
                            " has " + std::to_string(count));
    }
  }
  if (first.empty())
    throw input_error(file, attributes_where, "attributes name none of TRANSLATION, ROTATION and SCALE");
  const size_t room =
      (budget.limit - std::min(budget.limit, budget.placed)) / std::max<size_t>(budget.per_instance, 1);
  if (count > room)
    throw input_error(file, pointer_join(attributes_where, first),
                      std::to_string(count) + " instances take the scene past the limit of " +
                          std::to_string(budget.limit) + " instances (--max-instances)");

  std::vector<float> values[3];
  for (int a = 0; a < 3; ++a)
    if (accessors[a] >= 0)
      values[a] = read_values(model, accessors[a], file, pointer_join(attributes_where, names[a]));
  std::vector<dmat4> transforms(count);
  for (size_t i = 0; i < count; ++i) {
    const std::vector<float>& t = values[0];
    const std::vector<float>& r = values[1];
    const std::vector<float>& s = values[2];
    const dvec3 translation = t.empty() ? dvec3(0.0) : dvec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]);
    const dvec4 rotation =
        r.empty() ? dvec4(0, 0, 0, 1) : dvec4(r[4 * i], r[4 * i + 1], r[4 * i + 2], r[4 * i + 3]);
    const dvec3 scale = s.empty() ? dvec3(1.0) : dvec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]);
    if (rotation == dvec4(0.0))
      throw input_error(file, pointer_join(attributes_where, "ROTATION"),
                        "instance " + std::to_string(i) + " has a zero-length rotation quaternion");
    transforms[i] = trs_matrix(translation, rotation, scale);
  }
  return transforms;
}

}  // namespace kiln::gltf_internal
