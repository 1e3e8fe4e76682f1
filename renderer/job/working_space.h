// The render's working space (--working-space, --ocio-config, $OCIO): resolved through the colour
// module (OpenColorIO) only when one is named, applied to a loaded scene once, and described for
// the EXR header. Without --working-space nothing is loaded or converted: glTF's linear Rec.709.
#pragma once

#include <optional>
#include <string>

#include "core/math.h"
#include "io/colour/colour_module.h"
#include "job/colour_primaries.h"
#include "job/render_options.h"
#include "scene/colour_conversion.h"
#include "scene/scene.h"

namespace kiln {

class memory_budget;

struct working_space {
  std::string name;    // the config's name for it; empty: linear Rec.709, unconverted
  std::string config;  // the config file it came from
  dmat3 from_rec709{1.0};
  chromaticities primaries = rec709_primaries();

  bool converts() const { return !name.empty(); }
};

// The working space options name; a config given with --ocio-config alone is only checked.
// Throws kiln::error (input) naming the config and option for a missing or broken config or an
// unusable space, (io) when the colour module cannot be opened.
working_space resolve_working_space(const render_options& options);

// The preview's display transform: the config's display/view (--display, --view, else its
// defaults) from the working space, when a config is given (--ocio-config, $OCIO), a working space
// is set, or --display or --view is given; else nullopt, and the preview keeps the exact sRGB curve.
std::optional<display_transform> preview_view(const render_options& options);

// Converts s's colours into ws (scene/colour_conversion.h) and charges what its images grow by.
void apply_working_space(scene& s, const working_space& ws, memory_budget* memory,
                         const colour_conversion_scope& scope = {});

}  // namespace kiln
