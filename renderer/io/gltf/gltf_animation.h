// glTF 2.0 animations (§3.11): the chosen animations' channels sampled at one time into the
// nodes' local transforms and morph weights. The loader poses the scene it builds with them, so a
// posed scene is a function of (file, animation choice, time). Internal to io/gltf; bad input
// throws kiln::error (input) naming the JSON pointer, e.g. /animations/0/samplers/2/input.
#pragma once

#include <tiny_gltf.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"

namespace kiln::gltf_internal {

enum class keyframe_interpolation { step, linear, cubic_spline };

// Samples one keyframe track at time t into out[0..components). times: the keys, strictly
// increasing. values: one element of `components` per key, or for cubic_spline three per key
// (in-tangent, value, out-tangent, as glTF stores them). Times before the first key or after the
// last hold the end values. LINEAR on a rotation (components 4, `rotation`) is the shortest-path
// slerp of the normalized quaternions; every rotation result is normalized. CUBICSPLINE is the
// cubic Hermite spline with the tangents scaled by the key interval (glTF 2.0 Appendix C).
void sample_keyframes(const std::vector<float>& times, const std::vector<float>& values, size_t components,
                      keyframe_interpolation interpolation, bool rotation, double t, double* out);

// One node's animated state. Members not animated keep the node's own values.
struct animated_node {
  bool transform = false;  // a translation, rotation or scale channel drives it
  dvec3 translation{0.0};
  dvec4 rotation{0, 0, 0, 1};  // x, y, z, w
  dvec3 scale{1.0};
  bool weights = false;  // a weights channel drives it
  std::vector<double> morph_weights;
  // Whether the channels' keyframes differ, so the transform or the weights change with time; a
  // channel whose keys all hold one value poses the node alike at every time.
  bool transform_moves = false;
  bool weights_move = false;
};

// Every node's animated state (indexed by node), empty when no chosen animation drives a node.
struct animation_pose {
  std::vector<animated_node> nodes;
  std::vector<std::string> warnings;
  bool empty() const { return nodes.empty(); }
};

// The animations `which` names: "" or "all" every animation, "none" none (the rest pose: skins in
// their bind pose by the nodes' own transforms, morph targets by the default weights), else a name
// or an index. Throws
// kiln::error (input, location --animation) naming the known animations when none matches.
std::vector<int> chosen_animations(const tinygltf::Model& model, const std::string& which,
                                   const std::string& file);

// The first and last keyframe times of the chosen animations' samplers ({0, 0} without keys).
// Throws kiln::error (input) for keyframe times that are not finite and increasing.
std::pair<double, double> animation_time_range(const tinygltf::Model& model,
                                               const std::vector<int>& animations, const std::string& file);

// Evaluates the chosen animations at `time` seconds (finite). When two chosen animations drive
// the same property of a node, the first in document order wins and a warning says so.
animation_pose evaluate_animations(const tinygltf::Model& model, const std::vector<int>& animations,
                                   double time, const std::string& file);

// The number of morph targets of a mesh (every primitive must have the same; throws otherwise).
size_t morph_target_count(const tinygltf::Model& model, int mesh, const std::string& file);

}  // namespace kiln::gltf_internal
