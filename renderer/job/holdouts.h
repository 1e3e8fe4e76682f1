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
// holdouts (invisible ones when `invisible`). kiln::error naming the option: a pattern that selects
// no geometry (with a "did you mean" and the node names), or an exact name that selects two separate
// subtrees (with their paths).
void apply_holdouts(scene& world, const std::string& holdout, const std::string& only, bool invisible);

}  // namespace kiln
