// `kiln render`'s storage options (--float, --channel-format, --compression, --compression-level,
// --tiled, --multipart) and preview options (--preview, --preview-exposure), and their checks.
// CLI only: the rules themselves live in io/exr.
#pragma once

#include "app/render_command.h"

namespace kiln {

// Declares the storage and preview options on app, writing into options.
void add_exr_options(CLI::App& app, render_options& options);

// The writer's settings from the options: --float, then each --channel-format entry. Throws
// kiln::error (input) for a level the codec does not take, a lossy codec that would reach a data
// layer of a single-part file, or a preview without the beauty AOV. Called before rendering.
exr_settings resolve_exr_settings(const render_options& options);

}  // namespace kiln
