// Light groups: the beauty split by where its light came from. Every punctual light of the scene
// (the default headlight too) is a group, followed by emission (emissive and unlit surfaces) and
// the environment (what rays that leave the scene see); each group holds that source's light
// through the whole ray tree (seen directly, in mirrors, through glass), so the groups sum to the
// beauty. Depends on scene only.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace kiln {

// The EXR layer of each group, in the order shade/path_record.h files them: "lightgroup_" + the
// light's name for each light in scene order, then "lightgroup_emission" and
// "lightgroup_environment". A name keeps letters, digits and '_' (anything else becomes '_'); a
// light without a name is "light<index>"; a name met before gets "_2", "_3", ... so every layer is
// unique, and the two source groups keep their names.
std::vector<std::string> light_group_layers(const scene& world);

// The number of groups: the lights plus emission and environment.
inline int light_group_count(const scene& world) { return int(world.lights.size()) + 2; }

}  // namespace kiln
