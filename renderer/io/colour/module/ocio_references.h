// The references between a config's colour spaces, named transforms, looks and view transforms,
// checked before OpenColorIO builds any processor from them: OpenColorIO 2.1 follows them
// recursively with no guard, so a loop overflows the stack and a wide fan-out runs for hours.
// Internal to the colour module; reads the config through OpenColorIO's API only.
#pragma once

#include <OpenColorIO/OpenColorIO.h>

#include "io/colour/colour_module.h"

namespace kiln::colour_module {

// Checks the objects that a processor for `conversion` would reach (only those: a loop in a part of
// the config kiln does not use costs nothing). Throws kiln::error (input) naming config.path, the
// object where the trouble starts and the chain of references, when they loop, nest deeper than
// OpenColorIO's recursion can take, or branch into more paths than it could follow in good time.
void check_references(const OCIO_NAMESPACE::Config& cfg,
                      const OCIO_NAMESPACE::ConstTransformRcPtr& conversion,
                      const colour_config_source& config);

}  // namespace kiln::colour_module
