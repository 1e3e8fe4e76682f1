// How a render's EXR stores its layers, from the options: --float, --channel-format,
// --compression and its level, --tiled/--exr-tile-size, --multipart. The rules themselves live in
// io/exr; this turns option values into the writer's settings and says what is wrong with them.
#pragma once

#include <string>

#include "job/render_options.h"

namespace kiln {

// "beauty, N, albedo, ...": the AOVs --channel-format (and --float) choose a format for.
const std::string& selectable_format_aovs();

// "beauty, N, albedo, ...": the AOVs written as half unless --float or --channel-format says float.
const std::string& half_by_default_aovs();

// "rgba, depth, N, ...": every part --multipart can write, from the writer's table.
std::string exr_part_list();

// Parses "AOV=half|float,..." onto formats. Throws kiln::error (input, "--channel-format") for
// unknown names, a data AOV (Z, P, id) asked to be half, and text that is not AOV=FORMAT.
void apply_channel_formats(const std::string& text, layer_formats& formats);

// The writer's settings from the options: --float, then each --channel-format entry. Throws
// kiln::error (input) for a level the codec does not take, a lossy codec that would reach a data
// layer of a single-part file, or a preview without the beauty AOV. Called before rendering.
exr_settings resolve_exr_settings(const render_options& options);

}  // namespace kiln
