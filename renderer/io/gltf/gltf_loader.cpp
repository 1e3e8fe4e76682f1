// load_gltf: parse (gltf_parse), validate everything (gltf_validate), then build the scene:
// sample the chosen animations at the requested time (gltf_animation), flatten the chosen scene's
// node forest to double-precision world transforms, place one instance per node that uses a
// (mesh, primitive) pair (whose triangle mesh gltf_primitive_mesh builds once and shares), and
// convert the materials, lights and cameras the scene uses. A skinned or morphed mesh (non-zero or
// animated weights) is posed once per distinct pose (pose_key), which every node that poses it
// alike shares; a pose no animation changes is built once per sequence, like a rigid mesh.
#include "io/gltf/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>

#include "core/error.h"
#include "core/format_number.h"
#include "io/gltf/gltf_accessors.h"
#include "io/gltf/gltf_animation.h"
#include "io/gltf/gltf_build_context.h"
#include "io/gltf/gltf_common.h"
#include "io/gltf/gltf_draco.h"
#include "io/gltf/gltf_instancing.h"
#include "io/gltf/gltf_materials.h"
#include "io/gltf/gltf_memory.h"
#include "io/gltf/gltf_meshopt.h"
#include "io/gltf/gltf_parse.h"
#include "io/gltf/gltf_primitive_mesh.h"
#include "io/gltf/gltf_quadrics.h"
#include "io/gltf/gltf_summary.h"
#include "io/gltf/gltf_validate.h"
#include "io/gltf/gltf_variants.h"
#include "scene/coordinate_range.h"

namespace kiln {
namespace {

using namespace gltf_internal;

// A node's parent_from_node: its matrix (column-major), or T * R * S.
dmat4 local_transform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    dmat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[static_cast<size_t>(c * 4 + r)];
    return m;
  }
  const auto& t = node.translation;
  const auto& r = node.rotation;  // validation refused a zero quaternion
  const auto& s = node.scale;
  return trs_matrix(t.size() == 3 ? dvec3(t[0], t[1], t[2]) : dvec3(0.0),
                    r.size() == 4 ? dvec4(r[0], r[1], r[2], r[3]) : dvec4(0, 0, 0, 1),
                    s.size() == 3 ? dvec3(s[0], s[1], s[2]) : dvec3(1.0));
}

// A node's parent_from_node in the pose: the animated TRS when a channel drives it.
dmat4 posed_local(const build_context& ctx, int node_index) {
  if (!ctx.pose.empty()) {
    const animated_node& a = ctx.pose.nodes[static_cast<size_t>(node_index)];
    if (a.transform) return trs_matrix(a.translation, a.rotation, a.scale);
  }
  return local_transform(ctx.model.nodes[static_cast<size_t>(node_index)]);
}

// What a range problem of a node's world transform points at: the node's own matrix, translation
// or scale when that alone is out of range, else the node itself (its parents' transforms share
// the blame).
std::string range_pointer(const tinygltf::Node& node, int node_index) {
  const std::string base = pointer("nodes", node_index);
  if (node.matrix.size() == 16)
    return transform_range_problem(local_transform(node)) ? pointer_join(base, "matrix") : base;
  const auto& t = node.translation;
  if (t.size() == 3 && !(std::max({std::abs(t[0]), std::abs(t[1]), std::abs(t[2])}) <= max_coordinate))
    return pointer_join(base, "translation");
  const auto& s = node.scale;
  if (s.size() == 3 &&
      transform_range_problem(trs_matrix(dvec3(0.0), dvec4(0, 0, 0, 1), dvec3(s[0], s[1], s[2]))))
    return pointer_join(base, "scale");
  return base;
}

// Refuses a world position (camera, light) beyond max_coordinate; the node names the culprit.
void check_node_position(build_context& ctx, int node_index, const dmat4& world, const char* what) {
  const double reach = std::max({std::abs(world[3][0]), std::abs(world[3][1]), std::abs(world[3][2])});
  if (reach <= max_coordinate) return;
  throw input_error(ctx.file, range_pointer(ctx.model.nodes[static_cast<size_t>(node_index)], node_index),
                    std::string("the ") + what + " lies at " + format_coordinate(reach) +
                        ", beyond kiln's coordinate limit of " + format_coordinate(max_coordinate));
}

// The morph weights a node's mesh is posed with: a weights channel's, else the node's `weights`,
// else the mesh's, else zeros (glTF 2.0 §3.7.2.2); empty when its mesh has no morph targets.
std::vector<double> morph_weights(build_context& ctx, int node_index) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
  const size_t targets = morph_target_count(ctx.model, node.mesh, ctx.file);
  if (targets == 0) return {};
  if (!ctx.pose.empty() && ctx.pose.nodes[static_cast<size_t>(node_index)].weights)
    return ctx.pose.nodes[static_cast<size_t>(node_index)].morph_weights;
  const tinygltf::Mesh& src = ctx.model.meshes[static_cast<size_t>(node.mesh)];
  const bool own = !node.weights.empty();
  const std::vector<double>& defaults = own ? node.weights : src.weights;
  if (defaults.empty()) return std::vector<double>(targets, 0.0);
  const std::string where = own ? pointer_join(pointer("nodes", node_index), "weights")
                                : pointer_join(pointer("meshes", node.mesh), "weights");
  if (defaults.size() != targets)
    throw input_error(ctx.file, where,
                      "has " + std::to_string(defaults.size()) + " weights but the mesh has " +
                          std::to_string(targets) + " morph targets");
  for (double w : defaults)
    if (!std::isfinite(w)) throw input_error(ctx.file, where, "a weight is NaN or infinite");
  return defaults;
}

// Every node's world transform in the pose, and whether a channel moves it or an ancestor (with
// keys that differ), from the roots of the whole node forest (a skin's joints need not lie in the
// rendered scene).
void compute_node_worlds(build_context& ctx) {
  const size_t count = ctx.model.nodes.size();
  std::vector<char> is_child(count, 0);
  for (const tinygltf::Node& node : ctx.model.nodes)
    for (int child : node.children) is_child[static_cast<size_t>(child)] = 1;
  ctx.node_world.assign(count, dmat4(1.0));
  ctx.node_moves.assign(count, 0);
  std::vector<std::tuple<int, dmat4, bool>> stack;
  for (size_t n = count; n-- > 0;)
    if (!is_child[n]) stack.emplace_back(static_cast<int>(n), dmat4(1.0), false);
  while (!stack.empty()) {
    const auto [node_index, parent_world, parent_moves] = stack.back();
    stack.pop_back();
    const dmat4 world = parent_world * posed_local(ctx, node_index);
    const bool moves =
        parent_moves || (!ctx.pose.empty() && ctx.pose.nodes[size_t(node_index)].transform_moves);
    ctx.node_world[static_cast<size_t>(node_index)] = world;
    ctx.node_moves[static_cast<size_t>(node_index)] = moves;
    for (int child : ctx.model.nodes[static_cast<size_t>(node_index)].children)
      stack.emplace_back(child, world, moves);
  }
}

// The joint matrices of a skin: world(joint) * inverseBindMatrix (identity when absent).
const std::vector<dmat4>& skin_joint_matrices(build_context& ctx, int skin_index) {
  auto cached = ctx.skin_joints.find(skin_index);
  if (cached != ctx.skin_joints.end()) return cached->second;
  if (ctx.node_world.empty()) compute_node_worlds(ctx);
  const tinygltf::Skin& skin = ctx.model.skins[static_cast<size_t>(skin_index)];
  const std::string where = pointer("skins", skin_index);
  if (skin.joints.empty())
    throw input_error(ctx.file, pointer_join(where, "joints"), "a skin needs at least one joint");
  std::vector<float> inverse_bind;
  if (skin.inverseBindMatrices >= 0) {
    const std::string at = pointer_join(where, "inverseBindMatrices");
    const tinygltf::Accessor& acc = ctx.model.accessors[static_cast<size_t>(skin.inverseBindMatrices)];
    if (acc.type != TINYGLTF_TYPE_MAT4 || acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
      throw input_error(ctx.file, at,
                        "must be MAT4 FLOAT (got " + type_name(acc.type) + " " +
                            component_type_name(acc.componentType) + ")");
    if (acc.count < skin.joints.size())
      throw input_error(ctx.file, at,
                        "has " + std::to_string(acc.count) + " matrices for " +
                            std::to_string(skin.joints.size()) + " joints");
    inverse_bind = read_finite(ctx, skin.inverseBindMatrices, at, "inverseBindMatrices");
  }
  std::vector<dmat4> joints(skin.joints.size());
  for (size_t j = 0; j < joints.size(); ++j) {
    dmat4 ibm(1.0);
    if (!inverse_bind.empty())
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) ibm[c][r] = inverse_bind[16 * j + static_cast<size_t>(4 * c + r)];
    joints[j] = ctx.node_world[static_cast<size_t>(skin.joints[j])] * ibm;
  }
  return ctx.skin_joints.emplace(skin_index, std::move(joints)).first->second;
}

// How the node deforms its mesh, or nothing when it is placed rigidly (no skin, no weights
// channel, all morph weights zero): then its primitives are the shared meshes every other node
// uses.
std::optional<deformation> node_deformation(build_context& ctx, int node_index) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
  deformation d;
  d.weights = morph_weights(ctx, node_index);
  // Weights a channel drives keep their posed mesh even when all are zero at this time, so which
  // meshes a scene has does not depend on the time (frames of one shot share the structure).
  const bool animated = !ctx.pose.empty() && ctx.pose.nodes[static_cast<size_t>(node_index)].weights;
  if (!animated && std::all_of(d.weights.begin(), d.weights.end(), [](double w) { return w == 0.0; }))
    d.weights.clear();
  d.moves = animated && ctx.pose.nodes[static_cast<size_t>(node_index)].weights_move;
  if (node.skin >= 0) {
    d.skin = node.skin;
    d.joints = &skin_joint_matrices(ctx, node.skin);
    for (int joint : ctx.model.skins[static_cast<size_t>(node.skin)].joints)
      d.moves = d.moves || ctx.node_moves[static_cast<size_t>(joint)];
  }
  if (d.weights.empty() && d.joints == nullptr) return std::nullopt;
  return d;
}

// The scene mesh of a node's primitive: when the node deforms it, the posed mesh of its pose,
// built for the first node that poses it so (or taken over from the last frame when that pose
// does not move), else the shared rigid one.
int32_t mesh_for_node(build_context& ctx, int node_index, int prim_index, const deformation* posed) {
  const int mesh_index = ctx.model.nodes[static_cast<size_t>(node_index)].mesh;
  if (posed == nullptr) return mesh_for(ctx, mesh_index, prim_index);
  const bool animated_weights = !ctx.pose.empty() && ctx.pose.nodes[static_cast<size_t>(node_index)].weights;
  pose_key key{mesh_index, prim_index, posed->skin, animated_weights ? node_index : -1,
               animated_weights ? std::vector<double>() : posed->weights};
  auto cached = ctx.posed_cache.find(key);
  if (cached != ctx.posed_cache.end()) return cached->second;
  // A pose no animation moves is the last frame's mesh, taken over.
  const std::map<pose_key, int32_t>* last = ctx.reuse_poses;
  const auto previous = last ? last->find(key) : std::map<pose_key, int32_t>::const_iterator();
  const int32_t built = last && previous != last->end() ? take_over_mesh(ctx, previous->second)
                                                        : build_mesh(ctx, mesh_index, prim_index, posed);
  if (!posed->moves) ctx.still_poses.emplace(key, built);
  ctx.posed_cache.emplace(std::move(key), built);
  ctx.posed_primitives.emplace(mesh_index, prim_index);
  return built;
}

// Places every primitive of the node's mesh at `world`; false (nothing placed) when `world` is
// singular. Primitives are built first, so their data is checked even when nothing is placed.
bool place_primitives(build_context& ctx, int node_index, const dmat4& world, const std::string& where,
                      const deformation* posed) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
  const tinygltf::Mesh& src = ctx.model.meshes[static_cast<size_t>(node.mesh)];
  instance inst;
  inst.kind = shape_kind::mesh;
  inst.node = static_cast<uint32_t>(node_index);
  inst.world_from_object = world;
  finish_instance_transform(inst);
  const bool singular = !is_finite(inst.object_from_world) || glm::determinant(dmat3(world)) == 0.0;
  if (!singular)
    if (auto problem = transform_range_problem(world))
      throw input_error(ctx.file, where, "its world transform is out of range: " + *problem);
  for (size_t p = 0; p < src.primitives.size(); ++p) {
    const int32_t shape = mesh_for_node(ctx, node_index, static_cast<int>(p), posed);
    if (shape < 0 || singular) continue;
    inst.shape = static_cast<uint32_t>(shape);
    ctx.out.instances.push_back(inst);
    ctx.instance_gltf_material.push_back(src.primitives[p].material);
  }
  return !singular;
}

// A node's mesh: placed once, or once per EXT_mesh_gpu_instancing instance at
// world * node_from_instance (the node's transform is the instances' parent). A skinned mesh is
// posed in world space by its joints, so the node's own transform is ignored (glTF 2.0 §3.7.3).
void place_mesh(build_context& ctx, int node_index, const dmat4& node_world) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
  const std::optional<deformation> posed = node_deformation(ctx, node_index);
  const deformation* deform = posed ? &*posed : nullptr;
  const dmat4 world = node.skin >= 0 ? dmat4(1.0) : node_world;
  const instance_budget budget{ctx.out.instances.size(),
                               ctx.model.meshes[static_cast<size_t>(node.mesh)].primitives.size(),
                               ctx.max_instances};
  const auto instances = read_gpu_instances(ctx.model, node_index, ctx.quantized, budget, ctx.file);
  if (!instances) {
    if (!place_primitives(ctx, node_index, world, range_pointer(node, node_index), deform))
      warn_once(ctx,
                pointer("nodes", node_index) + ": singular transform (zero scale); its mesh is not placed");
    return;
  }
  size_t singular = 0;
  const std::string where =
      pointer_join(pointer_join(pointer("nodes", node_index), "extensions"), gpu_instancing_extension);
  for (const dmat4& node_from_instance : *instances)
    singular += !place_primitives(ctx, node_index, world * node_from_instance, where, deform);
  if (singular != 0)
    warn_once(ctx, pointer_join(pointer_join(pointer("nodes", node_index), "extensions"),
                                gpu_instancing_extension) +
                       ": " + std::to_string(singular) +
                       " instances have a singular transform (zero scale); they are not placed");
}

// A KILN_quadric placement: one instance of a shared definition. Unlike a mesh, a quadric
// with a singular transform is an error: its object-space ray would be undefined.
void place_quadric(build_context& ctx, int node_index, const quadric_placement& placement,
                   const dmat4& world) {
  instance inst;
  inst.kind = shape_kind::quadric;
  inst.shape = placement.primitive;
  inst.node = static_cast<uint32_t>(node_index);
  inst.world_from_object = world;
  finish_instance_transform(inst);
  if (!is_finite(inst.object_from_world) || glm::determinant(dmat3(world)) == 0.0)
    throw input_error(
        ctx.file, pointer_join(pointer_join(pointer("nodes", node_index), "extensions"), quadric_extension),
        "the node's transform is not invertible (zero scale); a quadric cannot be placed by it");
  if (auto problem = transform_range_problem(world))
    throw input_error(ctx.file, range_pointer(ctx.model.nodes[static_cast<size_t>(node_index)], node_index),
                      "its world transform is out of range: " + *problem);
  ctx.out.instances.push_back(inst);
  ctx.instance_gltf_material.push_back(placement.material);
}

// A camera frame without scale: keep the view direction (-Z) and the up vector (+Y) of the node.
void place_camera(build_context& ctx, int node_index, const dmat4& world) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
  const tinygltf::Camera& src = ctx.model.cameras[static_cast<size_t>(node.camera)];
  const dvec3 z = glm::normalize(dvec3(world[2]));
  const dvec3 y_raw = dvec3(world[1]) - glm::dot(dvec3(world[1]), z) * z;
  const dvec3 y = glm::normalize(y_raw);
  const dvec3 x = glm::cross(y, z);
  if (!is_finite(z) || !is_finite(y) || !is_finite(x) || glm::length(y_raw) == 0.0) {
    warn_once(ctx,
              pointer("nodes", node_index) + ": camera node transform is singular; the camera is skipped");
    return;
  }
  check_node_position(ctx, node_index, world, "camera");
  camera cam;
  cam.name = !src.name.empty() ? src.name : node.name;
  cam.world_from_camera = dmat4(dvec4(x, 0.0), dvec4(y, 0.0), dvec4(z, 0.0), dvec4(dvec3(world[3]), 1.0));
  if (src.type == "perspective") {
    cam.kind = projection::perspective;
    cam.yfov = static_cast<float>(src.perspective.yfov);
    cam.aspect_ratio = static_cast<float>(src.perspective.aspectRatio);
    cam.znear = static_cast<float>(src.perspective.znear);
  } else {
    cam.kind = projection::orthographic;
    // The view's half-extents become ray origins: they obey the coordinate limit too.
    for (const auto& [key, value] :
         {std::pair{"xmag", src.orthographic.xmag}, std::pair{"ymag", src.orthographic.ymag}})
      if (!(std::abs(value) <= max_coordinate))
        throw input_error(ctx.file,
                          pointer_join(pointer_join(pointer("cameras", node.camera), "orthographic"), key),
                          format_coordinate(value) + " is beyond kiln's coordinate limit of " +
                              format_coordinate(max_coordinate));
    cam.xmag = static_cast<float>(src.orthographic.xmag);
    cam.ymag = static_cast<float>(src.orthographic.ymag);
    cam.znear = static_cast<float>(src.orthographic.znear);
  }
  ctx.out.cameras.push_back(cam);
}

void place_light(build_context& ctx, int node_index, int light_index, const dmat4& world) {
  const tinygltf::Light& src = ctx.model.lights[static_cast<size_t>(light_index)];
  light l;
  l.name = src.name;
  l.kind = src.type == "spot"          ? light_kind::spot
           : src.type == "directional" ? light_kind::directional
                                       : light_kind::point;
  if (src.color.size() == 3)
    l.color = vec3(static_cast<float>(src.color[0]), static_cast<float>(src.color[1]),
                   static_cast<float>(src.color[2]));
  l.intensity = static_cast<float>(src.intensity);
  l.range = static_cast<float>(src.range);
  l.inner_cone_angle = static_cast<float>(src.spot.innerConeAngle);
  l.outer_cone_angle = static_cast<float>(src.spot.outerConeAngle);
  if (l.kind != light_kind::directional) check_node_position(ctx, node_index, world, "light");
  l.position = transform_point(world, dvec3(0.0));
  const dvec3 dir = transform_vector(world, dvec3(0.0, 0.0, -1.0));
  const double len = glm::length(dir);
  if (l.kind != light_kind::point) {
    if (!(len > 0.0) || !std::isfinite(len)) {
      warn_once(ctx,
                pointer("nodes", node_index) + ": light node transform is singular; the light is skipped");
      return;
    }
    l.direction = vec3(dir / len);
  }
  ctx.out.lights.push_back(l);
}

// Walks the scene's node forest iteratively (validation proved it acyclic) in document order.
void place_nodes(build_context& ctx, const std::vector<int>& roots) {
  std::vector<std::pair<int, dmat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, dmat4(1.0));
  while (!stack.empty()) {
    const auto [node_index, parent_world] = stack.back();
    stack.pop_back();
    const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(node_index)];
    const dmat4 world = parent_world * posed_local(ctx, node_index);
    if (!is_finite(world))
      throw input_error(ctx.file, pointer("nodes", node_index), "world transform overflows to infinity");
    if (node.mesh >= 0) place_mesh(ctx, node_index, world);
    if (auto placement = read_quadric_placement(ctx.model, node_index, ctx.out.quadrics.size(), ctx.file))
      place_quadric(ctx, node_index, *placement, world);
    if (node.camera >= 0) place_camera(ctx, node_index, world);
    const int light_index = node_light_index(node);
    if (light_index >= 0) place_light(ctx, node_index, light_index, world);
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.emplace_back(*it, world);
  }
}

// The scene material of each glTF material the instances use (-1: the default material).
using material_map = std::map<int, uint32_t>;

std::set<int> used_materials(const build_context& ctx) {
  return std::set<int>(ctx.instance_gltf_material.begin(), ctx.instance_gltf_material.end());
}

// Converts the materials instances use, in glTF order, then the default material last if needed.
material_map convert_used_materials(build_context& ctx) {
  const std::set<int> used = used_materials(ctx);
  texture_remap remap = make_texture_remap(ctx.model);
  remap.max_texels = ctx.max_texels;
  remap.memory = ctx.memory;
  material_map scene_index;
  try {
    for (int gltf_material : used) {
      if (gltf_material < 0) continue;
      ctx.out.materials.push_back(convert_material(ctx.model, gltf_material, remap, ctx.out, ctx.file));
      ctx.out.materials.back().source_index = gltf_material;
      scene_index[gltf_material] = static_cast<uint32_t>(ctx.out.materials.size() - 1);
    }
  } catch (...) {
    // Images used to decode as materials converted: one queued before this error that does not
    // decode is still the error reported, whatever the thread count.
    decode_used_images(remap, ctx.out, ctx.file, ctx.threads);
    throw;
  }
  decode_used_images(remap, ctx.out, ctx.file, ctx.threads);
  if (used.count(-1) != 0 || ctx.out.materials.empty()) {
    ctx.out.materials.push_back(default_material());
    ctx.out.materials.back().source_index = static_cast<int32_t>(ctx.model.materials.size());
    scene_index[-1] = static_cast<uint32_t>(ctx.out.materials.size() - 1);
  }
  return scene_index;
}

void assign_materials(build_context& ctx, const material_map& scene_index) {
  for (size_t i = 0; i < ctx.out.instances.size(); ++i)
    ctx.out.instances[i].material = scene_index.at(ctx.instance_gltf_material[i]);
}

// Index values are checked while a primitive is built; primitives the chosen scene does not
// place are never built, yet an out-of-range index there still marks a broken file.
void check_unplaced_indices(build_context& ctx) {
  for (size_t m = 0; m < ctx.model.meshes.size(); ++m) {
    const auto& primitives = ctx.model.meshes[m].primitives;
    for (size_t p = 0; p < primitives.size(); ++p) {
      const auto key = std::make_pair(static_cast<int>(m), static_cast<int>(p));
      if (ctx.mesh_cache.count(key) != 0 || ctx.posed_primitives.count(key) != 0 || primitives[p].indices < 0)
        continue;
      const size_t vertex_count =
          ctx.model.accessors[static_cast<size_t>(primitives[p].attributes.at("POSITION"))].count;
      primitive_indices(ctx, primitives[p], vertex_count, primitive_pointer(key.first, key.second));
    }
  }
}

int chosen_scene(const tinygltf::Model& model, const gltf_load_options& options, const std::string& file) {
  const int count = static_cast<int>(model.scenes.size());
  const auto missing = [&](int index, const std::string& where) {
    return input_error(file, where,
                       "/scenes/" + std::to_string(index) + " does not exist (file has " +
                           std::to_string(count) + " scenes)");
  };
  if (options.scene_index >= 0) {
    if (options.scene_index >= count) throw missing(options.scene_index, "");
    return options.scene_index;
  }
  if (model.defaultScene >= 0) return model.defaultScene;  // validated to be in range
  return count > 0 ? 0 : -1;
}

}  // namespace

// What a sequence keeps between frames: the parsed file, and what its last frame was built from.
struct gltf_sequence::state {
  std::string path;
  gltf_load_options options;
  memory_charge model_memory;  // released once the model is gone
  tinygltf::Model model;
  bool quantized = false;
  std::vector<int> animations;  // the chosen ones; empty: the file is posed without animations
  bool animated = false;
  std::set<std::string> warned;  // across frames: each distinct warning once per sequence
  // The last frame's:
  bool posed_once = false;
  std::map<std::vector<int>, int32_t> geometry_cache;
  std::map<pose_key, int32_t> still_poses;
  std::set<int> used;
  material_map materials;
  size_t image_count = 0;  // images the loader made (a client may append its own)
  uint64_t posed_bytes = 0;

  state(const std::string& p, const gltf_load_options& o) : path(p), options(o), model_memory(o.memory) {}
};

gltf_sequence::gltf_sequence(const std::string& path, const gltf_load_options& options)
    : state_(std::make_unique<state>(path, options)) {
  state& st = *state_;
  st.model = parse_gltf_file(path, options, &st.model_memory);
  // Compressed data is decoded into buffers of its own first, so that validation checks it like
  // any stored data: meshopt bufferViews (which a Draco stream could sit in), then Draco.
  decode_meshopt_views(st.model, path, &st.model_memory);
  decode_draco_primitives(st.model, path, &st.model_memory);
  validate_model(st.model, path);
  apply_material_variant(st.model, options.variant, path);
  chosen_scene(st.model, options, path);  // a bad --scene fails the load, before any pose
  st.quantized = uses_extension(st.model, quantization_extension);
  // A still asset (no animation) skips this: its scene is what it always was.
  st.animated = !st.model.animations.empty() ||
                !(options.animation.empty() || options.animation == "all" || options.animation == "none");
  if (st.animated) st.animations = chosen_animations(st.model, options.animation, path);
}

gltf_sequence::~gltf_sequence() = default;

bool gltf_sequence::animated() const { return state_->animated && !state_->animations.empty(); }

gltf_summary gltf_sequence::summary() const { return summarize_model(state_->model, state_->path); }

std::pair<double, double> gltf_sequence::time_range() const {
  if (!animated()) return {0.0, 0.0};
  return animation_time_range(state_->model, state_->animations, state_->path);
}

scene gltf_sequence::pose(double time, scene* previous, std::vector<uint32_t>* posed_meshes) {
  state& st = *state_;
  const tinygltf::Model& model = st.model;
  const std::string& path = st.path;
  const bool reuse = previous != nullptr && st.posed_once;
  st.posed_once = false;  // a pose that throws leaves `previous` half taken: the next builds afresh
  scene out;
  out.source = path;
  build_context ctx{model,
                    path,
                    st.options.limits.max_instances,
                    st.options.limits.max_texels,
                    st.options.threads,
                    st.quantized,
                    out,
                    {},
                    {},
                    st.warned};
  ctx.memory = st.options.memory;
  if (reuse) {
    ctx.reuse = previous;
    ctx.reuse_geometry = &st.geometry_cache;
    ctx.reuse_poses = &st.still_poses;
  }

  // Optional extensions kiln does not know are ignored, all named on one line (required ones
  // were refused while parsing).
  const auto& supported = supported_extensions();
  std::vector<std::string> unsupported;
  for (const std::string& name : model.extensionsUsed)
    if (std::find(supported.begin(), supported.end(), name) == supported.end())
      unsupported.push_back(shown(name));
  if (unsupported.size() == 1)
    warn_once(ctx, "extension " + unsupported[0] + " is not supported; it is ignored");
  if (unsupported.size() > 1) {
    std::string names = unsupported[0];
    for (size_t i = 1; i < unsupported.size(); ++i) names += ", " + unsupported[i];
    warn_once(ctx, "extensions " + names + " are not supported; they are ignored");
  }
  if (!std::isfinite(time)) throw input_error(path, "--time", "the time must be a finite number of seconds");
  if (st.animated) {
    ctx.pose = evaluate_animations(model, st.animations, time, path);
    for (const std::string& warning : ctx.pose.warnings) warn_once(ctx, warning);
  }

  out.quadrics = read_quadric_definitions(model, path);
  out.node_names.reserve(model.nodes.size());
  for (const tinygltf::Node& node : model.nodes) out.node_names.push_back(node.name);
  out.node_parents.assign(model.nodes.size(), -1);  // validation left a forest: one parent at most
  for (size_t n = 0; n < model.nodes.size(); ++n)
    for (int child : model.nodes[n].children) out.node_parents[static_cast<size_t>(child)] = int32_t(n);
  const int scene_index = chosen_scene(model, st.options, path);
  if (scene_index < 0)
    warn_once(ctx, "the file has no scenes; nothing is placed");
  else
    place_nodes(ctx, model.scenes[static_cast<size_t>(scene_index)].nodes);
  if (!reuse) check_unplaced_indices(ctx);  // the file does not change between frames

  // Materials do not animate: a frame that uses the same ones as the last takes them over, with
  // their textures and decoded images.
  const std::set<int> used = used_materials(ctx);
  if (reuse && used == st.used) {
    out.materials = std::move(previous->materials);
    out.textures = std::move(previous->textures);
    const size_t images = std::min(st.image_count, previous->images.size());
    out.images.assign(
        std::make_move_iterator(previous->images.begin()),
        std::make_move_iterator(previous->images.begin() + static_cast<std::ptrdiff_t>(images)));
  } else {
    st.materials = convert_used_materials(ctx);
    st.used = used;
  }
  assign_materials(ctx, st.materials);
  st.image_count = out.images.size();

  // The last frame's posed meshes are the caller's to drop now; this frame's are charged instead.
  if (ctx.memory) ctx.memory->release(st.posed_bytes);
  st.posed_bytes = ctx.posed_bytes;
  st.geometry_cache = std::move(ctx.geometry_cache);
  st.still_poses = std::move(ctx.still_poses);
  st.posed_once = true;
  if (posed_meshes) *posed_meshes = std::move(ctx.posed_meshes);
  // Each warning is new once a sequence, so the warnings of a pose its caller only looked at (a
  // shot's framing poses, shutter steps, motion neighbours) come along with the next.
  if (previous) {
    out.stats.warnings.insert(out.stats.warnings.begin(), previous->stats.warnings.begin(),
                              previous->stats.warnings.end());
    previous->stats.warnings.clear();
  }
  return out;
}

std::vector<std::string> gltf_material_variants(const std::string& path, const gltf_load_options& options) {
  memory_charge held(options.memory);
  const tinygltf::Model model = parse_gltf_file(path, options, &held);
  return material_variant_names(model, path);
}

scene load_gltf(const std::string& path, const gltf_load_options& options) {
  gltf_sequence sequence(path, options);
  return sequence.pose(options.time);
}

}  // namespace kiln
