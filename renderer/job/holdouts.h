// Holdout mattes and render layers (--holdout, --only, --holdout-invisible): marks the scene's
// instances whose glTF node matches a pattern. Depends on scene and core only.
#pragma once

#include <string>

#include "scene/scene.h"

namespace kiln {

// holdout and only are comma-separated lists of node names or shell globs (`*`, `?`, `[...]`,
// matched by fnmatch against the glTF node name, `node<index>` when unnamed, as Cryptomatte names
// objects). Instances of nodes matching `holdout`, and with `only` every instance of a node that
// matches none of `only`, become holdouts (invisible ones when `invisible`). A pattern that matches
// no node is a typo: kiln::error naming the option and the pattern, with the node names.
void apply_holdouts(scene& world, const std::string& holdout, const std::string& only, bool invisible);

}  // namespace kiln
