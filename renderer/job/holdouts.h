// Holdout mattes and render layers (--holdout, --only, --holdout-invisible): marks the scene's
// instances whose glTF node, or an ancestor of it, matches a pattern. Depends on scene and core only.
#pragma once

#include <string>

#include "scene/scene.h"

namespace kiln {

// holdout and only are comma-separated lists of node names, node paths or shell globs of either
// (`*`, `?`, `[...]`, by fnmatch). A name is the glTF node's (`node<index>` when unnamed, as
// Cryptomatte names objects); a pattern with a '/' is a path of names from the root
// ("/cornell_box/objects", or any tail of it: "objects/blue_ball"). A node selects its whole subtree.
// Instances selected by `holdout`, and with `only` every instance not selected by it, become
// holdouts of kind `others`. kiln::error naming the option: a pattern that selects
// no geometry (with a "did you mean" and the node names), or an exact name that selects two separate
// subtrees (with their paths).
void apply_holdouts(scene& world, const std::string& holdout, const std::string& only, holdout_kind others);

// What --others (auto, invisible, matte), --holdout-invisible and --deep make of the instances
// outside a layer: auto is invisible for a deep render (a deep merge does the holdout) and matte
// for a flat one (flat layers add with `plus`); --holdout-invisible turns a matte into an invisible
// one. --others invisible with --holdout-invisible contradict each other: kiln::error.
holdout_kind others_kind(const std::string& others, bool holdout_invisible, bool deep);

}  // namespace kiln
