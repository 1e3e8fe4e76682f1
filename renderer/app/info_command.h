// `kiln info ASSET [--json]`: what an asset holds (cameras, animations, variants, lights, scenes,
// the node tree with its geometry, bounds, extensions and kiln's support for each) and an estimate
// of the render the view options describe, as text or one JSON document (job/asset_info.h).
// App layer: arguments and printing only.
#pragma once

#include "job/render_options.h"

namespace CLI {
class App;
}

namespace kiln {

struct info_options {
  render_options view;  // the asset and the render whose cost is estimated
  bool json = false;
};

void add_info_options(CLI::App& app, info_options& options);

// Prints the info to stdout. Throws kiln::error as kiln render does for bad input.
void run_info(const info_options& options);

}  // namespace kiln
