#include "io/gltf/gltf_quadrics.h"

#include <cmath>
#include <map>

#include "core/error.h"
#include "core/format_number.h"
#include "core/message_text.h"
#include "geometry/quadric.h"
#include "io/gltf/gltf_common.h"
#include "scene/coordinate_range.h"

namespace kiln::gltf_internal {

namespace {

// Reads one definition's fields with the JSON path of each for error messages.
class definition_reader {
 public:
  definition_reader(const tinygltf::Value& value, std::string where, const std::string& file)
      : value_(value), where_(std::move(where)), file_(file) {}

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const {
    throw input_error(file_, key.empty() ? where_ : pointer_join(where_, key), reason);
  }

  bool has(const std::string& key) const { return value_.Has(key); }

  // A required finite number.
  double number(const std::string& key) const {
    if (!value_.Has(key)) fail("", "missing parameter '" + key + "'");
    return checked_number(key);
  }

  // An optional finite number.
  double number(const std::string& key, double fallback) const {
    return value_.Has(key) ? checked_number(key) : fallback;
  }

  // A required number > 0.
  double positive(const std::string& key) const {
    const double v = number(key);
    if (!(v > 0.0)) fail(key, "'" + key + "' must be greater than 0, got " + format_number(v));
    return v;
  }

  bool flag(const std::string& key) const {
    if (!value_.Has(key)) return false;
    const tinygltf::Value& v = value_.Get(key);
    if (!v.IsBool()) fail(key, "'" + key + "' must be true or false");
    return v.Get<bool>();
  }

  // A fixed-length array of finite numbers.
  std::vector<double> numbers(const std::string& key, size_t count) const {
    const tinygltf::Value& v = value_.Get(key);
    if (!v.IsArray() || v.ArrayLen() != count)
      fail(key, "'" + key + "' must be an array of " + std::to_string(count) + " numbers");
    std::vector<double> out(count);
    for (size_t i = 0; i < count; ++i) {
      const tinygltf::Value& e = v.Get(int(i));
      if (!e.IsNumber() || !std::isfinite(e.GetNumberAsDouble()))
        fail(key, "element " + std::to_string(i) + " of '" + key + "' is not a finite number");
      out[i] = e.GetNumberAsDouble();
    }
    return out;
  }

 private:
  double checked_number(const std::string& key) const {
    const tinygltf::Value& v = value_.Get(key);
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble()))
      fail(key, "'" + key + "' must be a finite number");
    return v.GetNumberAsDouble();
  }

  const tinygltf::Value& value_;
  std::string where_;
  const std::string& file_;
};

const std::map<std::string, quadric_kind>& kind_names() {
  static const std::map<std::string, quadric_kind> names = {
      {"sphere", quadric_kind::sphere},
      {"cylinder", quadric_kind::cylinder},
      {"cone", quadric_kind::cone},
      {"paraboloid", quadric_kind::paraboloid},
      {"hyperboloid_one_sheet", quadric_kind::hyperboloid_one_sheet},
      {"hyperboloid_two_sheets", quadric_kind::hyperboloid_two_sheets},
      {"disk", quadric_kind::disk},
      {"general", quadric_kind::general},
      {"torus", quadric_kind::torus}};
  return names;
}

// zmin < zmax from the definition, with defaults.
void read_z_range(const definition_reader& in, quadric& q, double zmin, double zmax) {
  q.zmin = in.number("zmin", zmin);
  q.zmax = in.number("zmax", zmax);
  if (!(q.zmin < q.zmax)) in.fail("zmax", "zmin must be less than zmax");
}

// The general quadric from ten coefficients or a symmetric column-major 4×4 matrix Q (pᵀQp = 0
// with p = (x, y, z, 1)), clipped to a required box.
void read_general(const definition_reader& in, quadric& q) {
  if (in.has("coefficients")) {
    const std::vector<double> k = in.numbers("coefficients", 10);
    for (int i = 0; i < 10; ++i) q.coefficients[i] = k[size_t(i)];
  } else if (in.has("matrix")) {
    const std::vector<double> m = in.numbers("matrix", 16);
    auto at = [&](int row, int col) { return m[size_t(col * 4 + row)]; };
    for (int r = 0; r < 4; ++r)
      for (int c = r + 1; c < 4; ++c)
        if (std::abs(at(r, c) - at(c, r)) > 1e-12 * (std::abs(at(r, c)) + std::abs(at(c, r))))
          in.fail("matrix", "matrix must be symmetric");
    const double k[10] = {at(0, 0),     at(1, 1),     at(2, 2),     2 * at(0, 1), 2 * at(0, 2),
                          2 * at(1, 2), 2 * at(0, 3), 2 * at(1, 3), 2 * at(2, 3), at(3, 3)};
    for (int i = 0; i < 10; ++i) q.coefficients[i] = k[i];
  } else {
    in.fail("", "missing parameter 'coefficients' (or 'matrix')");
  }
  bool any = false;
  for (double k : q.coefficients) any = any || k != 0.0;
  if (!any) in.fail("coefficients", "all coefficients are zero");
  if (!in.has("box_min")) in.fail("", "missing parameter 'box_min'");
  if (!in.has("box_max")) in.fail("", "missing parameter 'box_max'");
  const std::vector<double> lo = in.numbers("box_min", 3), hi = in.numbers("box_max", 3);
  q.box.lower = dvec3(lo[0], lo[1], lo[2]);
  q.box.upper = dvec3(hi[0], hi[1], hi[2]);
  if (!(q.box.lower.x < q.box.upper.x && q.box.lower.y < q.box.upper.y && q.box.lower.z < q.box.upper.z))
    in.fail("box_max", "box_max must exceed box_min on every axis");
}

quadric read_definition(const tinygltf::Value& value, const std::string& where, const std::string& file) {
  definition_reader in(value, where, file);
  if (!value.IsObject()) in.fail("", "a primitive definition must be an object");
  if (!value.Has("kind") || !value.Get("kind").IsString()) in.fail("", "missing parameter 'kind' (a string)");
  const std::string kind = value.Get("kind").Get<std::string>();
  auto found = kind_names().find(kind);
  if (found == kind_names().end()) {
    std::string known;
    for (const auto& entry : kind_names()) known += (known.empty() ? "" : ", ") + entry.first;
    in.fail("kind", "unknown kind " + quoted(kind) + " (expected one of: " + known + ")");
  }
  quadric q;
  q.kind = found->second;
  if (value.Has("name") && value.Get("name").IsString()) q.name = value.Get("name").Get<std::string>();
  switch (q.kind) {
    case quadric_kind::sphere:
      q.radius = in.positive("radius");
      break;
    case quadric_kind::cylinder:
      q.radius = in.positive("radius");
      read_z_range(in, q, -1.0, 1.0);
      q.caps = in.flag("caps");
      break;
    case quadric_kind::cone:
      q.radius = in.positive("radius");
      q.height = in.positive("height");
      read_z_range(in, q, 0.0, q.height);
      if (q.zmin < 0.0 || q.zmax > q.height)
        in.fail("zmax", "the cone is clipped to 0 <= zmin < zmax <= height");
      q.caps = in.flag("caps");
      break;
    case quadric_kind::paraboloid:
      q.radius = in.positive("radius");
      q.zmax = in.positive("zmax");
      read_z_range(in, q, 0.0, q.zmax);
      if (q.zmin < 0.0) in.fail("zmin", "a paraboloid lies in z >= 0: zmin must not be negative");
      q.caps = in.flag("caps");
      break;
    case quadric_kind::hyperboloid_one_sheet:
    case quadric_kind::hyperboloid_two_sheets:
      q.radius = in.positive("radius");
      q.c = in.positive("c");
      read_z_range(in, q, -1.0, 1.0);
      q.caps = in.flag("caps");
      if (q.kind == quadric_kind::hyperboloid_two_sheets && q.zmax <= q.c && q.zmin >= -q.c)
        in.fail("zmax", "the range [zmin, zmax] lies between the sheets (|z| < c): nothing to render");
      break;
    case quadric_kind::disk:
      q.radius = in.positive("radius");
      q.inner_radius = in.number("inner_radius", 0.0);
      if (q.inner_radius < 0.0 || q.inner_radius >= q.radius)
        in.fail("inner_radius", "inner_radius must be in [0, radius)");
      break;
    case quadric_kind::general:
      read_general(in, q);
      break;
    case quadric_kind::torus:
      q.major_radius = in.positive("major_radius");
      q.radius = in.positive("minor_radius");
      break;
  }
  q.bounds = quadric_bounds(q);
  // The canonical object space is where Embree's user geometry is bounded and rays arrive.
  if (!(max_abs_coordinate(q.bounds) <= max_coordinate))
    in.fail("", "its bounds reach " + format_coordinate(max_abs_coordinate(q.bounds)) +
                    ", beyond kiln's coordinate limit of " + format_coordinate(max_coordinate));
  return q;
}

// " (placed by /nodes/3 'name')": the nodes that use definition i, so that an error in a shared
// definition names what the user sees in their scene.
std::string users_of(const tinygltf::Model& model, size_t definition) {
  std::string users;
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    auto ext = model.nodes[n].extensions.find(quadric_extension);
    if (ext == model.nodes[n].extensions.end() || !ext->second.IsObject() || !ext->second.Has("primitive"))
      continue;
    const tinygltf::Value& index = ext->second.Get("primitive");
    if (!index.IsInt() || index.GetNumberAsInt() != int(definition)) continue;
    users += (users.empty() ? "" : ", ") + pointer("nodes", int64_t(n));
    if (!model.nodes[n].name.empty()) users += " " + quoted(model.nodes[n].name);
  }
  return users.empty() ? " (no node places it)" : " (placed by " + users + ")";
}

}  // namespace

std::vector<quadric> read_quadric_definitions(const tinygltf::Model& model, const std::string& file) {
  std::vector<quadric> out;
  auto ext = model.extensions.find(quadric_extension);
  if (ext == model.extensions.end()) return out;
  const std::string where = pointer_join("/extensions", quadric_extension);
  const tinygltf::Value& root = ext->second;
  if (!root.IsObject() || !root.Has("primitives") || !root.Get("primitives").IsArray())
    throw input_error(file, where, "expected an object with an array 'primitives'");
  const tinygltf::Value& list = root.Get("primitives");
  for (size_t i = 0; i < list.ArrayLen(); ++i) {
    try {
      out.push_back(read_definition(list.Get(int(i)),
                                    pointer_join(pointer_join(where, "primitives"), int64_t(i)), file));
    } catch (const error& e) {
      throw input_error(file, e.location(), e.reason() + users_of(model, i));
    }
  }
  return out;
}

std::optional<quadric_placement> read_quadric_placement(const tinygltf::Model& model, int node_index,
                                                        size_t definition_count, const std::string& file) {
  const tinygltf::Node& node = model.nodes[size_t(node_index)];
  auto ext = node.extensions.find(quadric_extension);
  if (ext == node.extensions.end()) return std::nullopt;
  const std::string where =
      pointer_join(pointer_join(pointer("nodes", node_index), "extensions"), quadric_extension);
  const tinygltf::Value& value = ext->second;
  if (!value.IsObject() || !value.Has("primitive") || !value.Get("primitive").IsInt())
    throw input_error(file, where, "expected an object with an integer 'primitive'");
  const int primitive = value.Get("primitive").GetNumberAsInt();
  if (primitive < 0 || size_t(primitive) >= definition_count)
    throw input_error(file, pointer_join(where, "primitive"),
                      "primitive " + std::to_string(primitive) + " does not exist (the file defines " +
                          std::to_string(definition_count) + " in /extensions/KILN_quadric/primitives)");
  quadric_placement placement;
  placement.primitive = uint32_t(primitive);
  if (value.Has("material")) {
    const tinygltf::Value& m = value.Get("material");
    if (!m.IsInt() || m.GetNumberAsInt() < 0 || size_t(m.GetNumberAsInt()) >= model.materials.size())
      throw input_error(
          file, pointer_join(where, "material"),
          "material must index /materials (the file has " + std::to_string(model.materials.size()) + ")");
    placement.material = m.GetNumberAsInt();
  }
  return placement;
}

}  // namespace kiln::gltf_internal
