// The references between a config's colour spaces, named transforms, looks and view transforms,
// checked before OpenColorIO builds any processor from them: OpenColorIO 2.1 follows them
// recursively with no guard, so a loop overflows the stack and a wide fan-out runs for hours.
// Internal to the colour module; reads the config through OpenColorIO's API only.
#pragma once

#include <OpenColorIO/OpenColorIO.h>

#include <string>
#include <vector>

#include "io/colour/colour_module.h"

namespace kiln::colour_module {

// A transform a config object holds, and where: "colour space 'ACEScg' [to_scene_reference]".
struct held_transform {
  OCIO_NAMESPACE::ConstTransformRcPtr transform;
  std::string where;
};

// Checks the objects that a processor for `conversion` would reach (only those: a loop in a part of
// the config kiln does not use costs nothing). Throws kiln::error (input) naming config.path, the
// object where the trouble starts and the chain of references, when they loop, nest deeper than
// OpenColorIO's recursion can take, or branch into more paths than it could follow in good time.
// Returns the transforms a processor for conversion may use: conversion itself and those of every
// object it reaches (both directions of each, as the walk follows them).
std::vector<held_transform> check_references(const OCIO_NAMESPACE::Config& cfg,
                                             const OCIO_NAMESPACE::ConstTransformRcPtr& conversion,
                                             const colour_config_source& config);

}  // namespace kiln::colour_module
