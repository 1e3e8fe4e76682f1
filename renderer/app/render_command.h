// `kiln render`: the option table on the command line, then one render job (job/render_job.h)
// with a progress line and a summary. The CLI's only job is to turn arguments into these calls.
#pragma once

#include "job/render_job.h"
#include "job/render_options.h"

namespace CLI {
class App;
}

namespace kiln {

// Declares the options every subcommand that renders shares (asset, image size, camera, samples,
// shading limits, threads, grid settings), writing into options. `kiln compare` reuses them.
void add_view_options(CLI::App& app, render_options& options);

// The view options without the asset positional (kiln batch takes many assets).
void add_view_settings(CLI::App& app, render_options& options);

// What render adds to the view options besides -o: the EXR's layers and storage, --crop, --band.
void add_image_options(CLI::App& app, render_options& options);

// Declares the render subcommand's options on app: the view options plus output and backend.
void add_render_options(CLI::App& app, render_options& options);

// prepare_scene for the CLI: SIGINT/SIGTERM stop the loading, warnings go to stderr unless -q.
prepared_scene prepare_cli_scene(const render_options& options);

struct render_fingerprint;

// Runs a render; the EXR records the fingerprint (computed here unless known). Throws
// kiln::error for bad input (kind input), I/O and render failures, or an interrupt.
void run_render(const render_options& options, const render_fingerprint* known = nullptr);

}  // namespace kiln
