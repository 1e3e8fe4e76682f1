#include "io/gltf/gltf_animation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "core/error.h"
#include "core/format_number.h"
#include "core/message_text.h"
#include "io/gltf/gltf_accessors.h"
#include "io/gltf/gltf_common.h"
#include "io/gltf/gltf_instancing.h"

namespace kiln::gltf_internal {
namespace {

// Zero stays zero (the caller refuses it), never NaN.
void normalize_quaternion(double* q) {
  const dvec4 unit = unit_quaternion(dvec4(q[0], q[1], q[2], q[3]));
  for (int j = 0; j < 4; ++j) q[j] = unit[j];
}

// Shortest-path spherical interpolation of two unit quaternions.
void slerp(const double* a, const double* b_in, double u, double* out) {
  double b[4] = {b_in[0], b_in[1], b_in[2], b_in[3]};
  double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  if (d < 0.0) {
    for (double& c : b) c = -c;
    d = -d;
  }
  double wa = 1.0 - u, wb = u;
  if (d < 0.9999995) {  // else nearly equal: linear weights, normalized below
    const double theta = std::acos(std::min(d, 1.0));
    const double s = std::sin(theta);
    wa = std::sin((1.0 - u) * theta) / s;
    wb = std::sin(u * theta) / s;
  }
  for (int j = 0; j < 4; ++j) out[j] = wa * a[j] + wb * b[j];
  normalize_quaternion(out);
}

bool is_float_or_normalized(const tinygltf::Accessor& acc, bool allow_normalized) {
  if (acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return true;
  if (!allow_normalized || !acc.normalized) return false;
  const int ct = acc.componentType;
  return ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         ct == TINYGLTF_COMPONENT_TYPE_SHORT || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
}

std::string format_accessor(const tinygltf::Accessor& acc) {
  return type_name(acc.type) + " " + component_type_name(acc.componentType) +
         (acc.normalized ? " normalized" : "");
}

keyframe_interpolation parse_interpolation(const std::string& name, const std::string& file,
                                           const std::string& where) {
  if (name.empty() || name == "LINEAR") return keyframe_interpolation::linear;
  if (name == "STEP") return keyframe_interpolation::step;
  if (name == "CUBICSPLINE") return keyframe_interpolation::cubic_spline;
  throw input_error(file, pointer_join(where, "interpolation"),
                    "unknown interpolation " + quoted(name) + " (LINEAR, STEP or CUBICSPLINE)");
}

// The keyframe times of a sampler: SCALAR FLOAT, finite and strictly increasing.
std::vector<float> read_times(const tinygltf::Model& model, int accessor, const std::string& file,
                              const std::string& where) {
  const tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(accessor)];
  if (acc.type != TINYGLTF_TYPE_SCALAR || acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    throw input_error(file, where, "keyframe times must be SCALAR FLOAT (got " + format_accessor(acc) + ")");
  std::vector<float> times = read_accessor_floats(model, accessor, file);
  for (size_t k = 0; k < times.size(); ++k) {
    if (!std::isfinite(times[k]))
      throw input_error(file, where, "keyframe time " + std::to_string(k) + " is NaN or infinite");
    if (k > 0 && !(times[k] > times[k - 1]))
      throw input_error(file, where,
                        "keyframe times must strictly increase (time " + std::to_string(k) + " is " +
                            format_number(times[k]) + ", after " + format_number(times[k - 1]) + ")");
  }
  return times;
}

// Whether a sampler's keyframes all hold one value (`stride` floats a key; CUBICSPLINE's value
// sits between its tangents, which must all be zero), so it gives that value at every time.
bool keyframes_hold(const std::vector<float>& values, size_t components, size_t stride, bool cubic) {
  const size_t value_at = cubic ? components : 0;
  for (size_t key = 0; key + stride <= values.size(); key += stride)
    for (size_t c = 0; c < stride; ++c) {
      const bool tangent = c < value_at || c >= value_at + components;
      if (tangent ? values[key + c] != 0.0f : values[key + c] != values[c]) return false;
    }
  return true;
}

}  // namespace

void sample_keyframes(const std::vector<float>& times, const std::vector<float>& values, size_t components,
                      keyframe_interpolation interpolation, bool rotation, double t, double* out) {
  const size_t n = times.size();
  const bool cubic = interpolation == keyframe_interpolation::cubic_spline;
  const size_t stride = cubic ? 3 * components : components;
  const size_t value_offset = cubic ? components : 0;
  const auto value = [&](size_t k, size_t j) { return double(values[k * stride + value_offset + j]); };
  const auto hold = [&](size_t k) {
    for (size_t j = 0; j < components; ++j) out[j] = value(k, j);
  };
  if (n == 1 || t <= times[0]) {
    hold(0);
  } else if (t >= times[n - 1]) {
    hold(n - 1);
  } else {
    const size_t k = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    const double t0 = times[k], t1 = times[k + 1];
    const double td = t1 - t0;
    const double u = (t - t0) / td;
    if (interpolation == keyframe_interpolation::step) {
      hold(k);
    } else if (interpolation == keyframe_interpolation::linear) {
      if (rotation) {
        double a[4], b[4];
        for (size_t j = 0; j < 4; ++j) {
          a[j] = value(k, j);
          b[j] = value(k + 1, j);
        }
        normalize_quaternion(a);
        normalize_quaternion(b);
        slerp(a, b, u, out);
        return;
      }
      for (size_t j = 0; j < components; ++j) out[j] = (1.0 - u) * value(k, j) + u * value(k + 1, j);
    } else {
      const double u2 = u * u, u3 = u2 * u;
      const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
      for (size_t j = 0; j < components; ++j) {
        const double out_tangent = values[k * stride + 2 * components + j];  // b_k
        const double in_tangent = values[(k + 1) * stride + j];              // a_(k+1)
        out[j] = h00 * value(k, j) + h10 * td * out_tangent + h01 * value(k + 1, j) + h11 * td * in_tangent;
      }
    }
  }
  if (rotation) normalize_quaternion(out);
}

std::pair<double, double> animation_time_range(const tinygltf::Model& model,
                                               const std::vector<int>& animations, const std::string& file) {
  double first = inf, last = -inf;
  for (int a : animations) {
    const tinygltf::Animation& animation = model.animations[static_cast<size_t>(a)];
    for (size_t i = 0; i < animation.samplers.size(); ++i) {
      const int input = animation.samplers[i].input;
      if (input < 0 || static_cast<size_t>(input) >= model.accessors.size()) continue;
      const std::string where =
          "/animations/" + std::to_string(a) + "/samplers/" + std::to_string(i) + "/input";
      const std::vector<float> times = read_times(model, input, file, where);
      if (times.empty()) continue;
      first = std::min(first, double(times.front()));
      last = std::max(last, double(times.back()));
    }
  }
  return first <= last ? std::make_pair(first, last) : std::make_pair(0.0, 0.0);
}

std::vector<int> chosen_animations(const tinygltf::Model& model, const std::string& which,
                                   const std::string& file) {
  const int count = static_cast<int>(model.animations.size());
  std::vector<int> all;
  for (int a = 0; a < count; ++a) all.push_back(a);
  if (which.empty() || which == "all") return all;
  if (which == "none") return {};
  if (count == 0) throw input_error(file, "--animation", "the file has no animations");
  const bool numeric = std::all_of(which.begin(), which.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (numeric && which.size() < 10) {
    const int index = std::stoi(which);
    if (index < count) return {index};
  }
  for (int a = 0; a < count; ++a)
    if (model.animations[static_cast<size_t>(a)].name == which) return {a};
  std::string known;
  for (int a = 0; a < count; ++a) {
    if (a == 8 && count > 9) {
      known += ", ... (" + std::to_string(count) + " in all)";
      break;
    }
    known += (a == 0 ? "" : ", ") + std::to_string(a);
    const std::string& name = model.animations[static_cast<size_t>(a)].name;
    if (!name.empty()) known += " " + quoted(name);
  }
  throw input_error(file, "--animation",
                    "no animation " + quoted(which) + " (animations: " + known + "; or all, or none)");
}

size_t morph_target_count(const tinygltf::Model& model, int mesh, const std::string& file) {
  const auto& primitives = model.meshes[static_cast<size_t>(mesh)].primitives;
  if (primitives.empty()) return 0;
  const size_t targets = primitives[0].targets.size();
  for (size_t p = 1; p < primitives.size(); ++p)
    if (primitives[p].targets.size() != targets)
      throw input_error(file,
                        pointer_join(pointer_join(pointer_join(pointer("meshes", mesh), "primitives"),
                                                  static_cast<int64_t>(p)),
                                     "targets"),
                        "primitive has " + std::to_string(primitives[p].targets.size()) +
                            " morph targets but primitive 0 has " + std::to_string(targets) +
                            " (every primitive of a mesh has the same)");
  return targets;
}

animation_pose evaluate_animations(const tinygltf::Model& model, const std::vector<int>& animations,
                                   double time, const std::string& file) {
  animation_pose pose;
  std::vector<animated_node> nodes(model.nodes.size());
  std::map<std::pair<int, std::string>, int> driver;  // (node, path) -> the animation that drives it
  // Properties a later animation drives too: a rig's clips each drive every bone, so one line says
  // how many, naming the first.
  std::string first_overlap;
  size_t overlaps = 0;
  std::vector<double> sample;
  bool any = false;
  for (int a : animations) {
    const tinygltf::Animation& anim = model.animations[static_cast<size_t>(a)];
    const std::string where = pointer("animations", a);
    for (size_t c = 0; c < anim.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = anim.channels[c];
      const std::string at = pointer_join(pointer_join(where, "channels"), static_cast<int64_t>(c));
      const std::string target = pointer_join(at, "target");
      if (channel.target_node < 0) continue;  // glTF: a channel without a node is ignored
      const std::string& path = channel.target_path;
      const bool rotation = path == "rotation";
      const bool weights = path == "weights";
      if (path == "pointer") {
        pose.warnings.push_back(target + ": KHR_animation_pointer channels are not supported; ignored");
        continue;
      }
      if (path != "translation" && !rotation && path != "scale" && !weights)
        throw input_error(
            file, pointer_join(target, "path"),
            "unknown animation path " + quoted(path) + " (translation, rotation, scale or weights)");
      const int node_index = channel.target_node;
      const tinygltf::Node& node = model.nodes[static_cast<size_t>(node_index)];
      if (!weights && node.matrix.size() == 16)
        throw input_error(
            file, pointer_join(target, "node"),
            pointer("nodes", node_index) +
                " has a matrix; an animated node may only have translation, rotation and scale");
      size_t components = rotation ? 4 : 3;
      if (weights) {
        components = node.mesh >= 0 ? morph_target_count(model, node.mesh, file) : 0;
        if (components == 0)
          throw input_error(file, pointer_join(target, "node"),
                            "a weights channel drives " + pointer("nodes", node_index) +
                                ", which has no mesh with morph targets");
      }
      const auto [owner, fresh] = driver.emplace(std::make_pair(node_index, path), a);
      if (!fresh) {
        if (owner->second == a)
          throw input_error(
              file, target,
              "a second channel of this animation drives " + path + " of " + pointer("nodes", node_index));
        if (overlaps++ == 0)
          first_overlap = "animations " + std::to_string(owner->second) + " and " + std::to_string(a) +
                          " both drive " + path + " of " + pointer("nodes", node_index);
        continue;
      }

      const std::string sp = pointer_join(pointer_join(where, "samplers"), channel.sampler);
      const tinygltf::AnimationSampler& sampler = anim.samplers[static_cast<size_t>(channel.sampler)];
      const keyframe_interpolation interpolation = parse_interpolation(sampler.interpolation, file, sp);
      const std::vector<float> times = read_times(model, sampler.input, file, pointer_join(sp, "input"));
      const std::string output_at = pointer_join(sp, "output");
      const tinygltf::Accessor& out = model.accessors[static_cast<size_t>(sampler.output)];
      const int type = weights ? TINYGLTF_TYPE_SCALAR : rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3;
      if (out.type != type || !is_float_or_normalized(out, rotation || weights))
        throw input_error(file, output_at,
                          path + " keyframes must be " +
                              (weights    ? "SCALAR FLOAT or normalized"
                               : rotation ? "VEC4 FLOAT or normalized"
                                          : "VEC3 FLOAT") +
                              " (got " + format_accessor(out) + ")");
      const bool cubic = interpolation == keyframe_interpolation::cubic_spline;
      const uint64_t expected = uint64_t(times.size()) * (cubic ? 3 : 1) * (weights ? components : 1);
      if (out.count != expected)
        throw input_error(file, output_at,
                          "has " + std::to_string(out.count) + " elements; " + std::to_string(times.size()) +
                              " keyframes" +
                              (cubic ? " of CUBICSPLINE (in-tangent, value, out-tangent)" : "") +
                              (weights ? " of " + std::to_string(components) + " morph weights" : "") +
                              " need " + std::to_string(expected) + " (the input accessor " +
                              std::to_string(sampler.input) + " has " + std::to_string(times.size()) + ")");
      const std::vector<float> values = read_accessor_floats(model, sampler.output, file);
      const size_t stride = cubic ? 3 * components : components;
      for (size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i]))
          throw input_error(file, output_at, "keyframe value " + std::to_string(i) + " is NaN or infinite");
      if (rotation)
        for (size_t k = 0; k < times.size(); ++k) {
          const float* q = &values[k * stride + (cubic ? components : 0)];
          if (q[0] == 0.0f && q[1] == 0.0f && q[2] == 0.0f && q[3] == 0.0f)
            throw input_error(file, output_at,
                              "keyframe " + std::to_string(k) + " is a zero-length rotation quaternion");
        }

      sample.assign(components, 0.0);
      sample_keyframes(times, values, components, interpolation, rotation, time, sample.data());
      // CUBICSPLINE's Hermite curve may pass through zero between nonzero keyframes (q to -q with
      // flat tangents): no rotation at all, which glTF cannot mean.
      if (rotation && sample[0] == 0.0 && sample[1] == 0.0 && sample[2] == 0.0 && sample[3] == 0.0)
        throw input_error(file, output_at,
                          "at time " + format_number(time) +
                              " the keyframes interpolate to a zero-length rotation quaternion");
      animated_node& state = nodes[static_cast<size_t>(node_index)];
      if (!state.transform && !weights) {
        // Start from the node's own TRS; the channels replace what they drive.
        const auto& t = node.translation;
        const auto& r = node.rotation;
        const auto& s = node.scale;
        if (t.size() == 3) state.translation = dvec3(t[0], t[1], t[2]);
        if (r.size() == 4) state.rotation = dvec4(r[0], r[1], r[2], r[3]);
        if (s.size() == 3) state.scale = dvec3(s[0], s[1], s[2]);
        state.transform = true;
      }
      const bool moves = !keyframes_hold(values, components, stride, cubic);
      if (path == "translation") state.translation = dvec3(sample[0], sample[1], sample[2]);
      if (rotation) state.rotation = dvec4(sample[0], sample[1], sample[2], sample[3]);
      if (path == "scale") state.scale = dvec3(sample[0], sample[1], sample[2]);
      if (weights) {
        state.weights = true;
        state.weights_move = moves;
        state.morph_weights = sample;
      } else {
        state.transform_moves = state.transform_moves || moves;
      }
      any = true;
    }
  }
  if (overlaps == 1)
    pose.warnings.push_back(first_overlap + "; the first wins (choose one with --animation)");
  if (overlaps > 1)
    pose.warnings.push_back(std::to_string(overlaps) +
                            " node properties are driven by more than one animation (" + first_overlap +
                            ", ...); the first wins (choose one with --animation)");
  if (any) pose.nodes = std::move(nodes);
  return pose;
}

}  // namespace kiln::gltf_internal
