#include "job/working_space.h"

#include "core/memory_budget.h"
#include "io/colour/colour_loader.h"
#include "scene/colour_conversion.h"

namespace kiln {

working_space resolve_working_space(const render_options& options) {
  working_space ws;
  // A config named on the command line is checked even when nothing uses it: a broken file the
  // user chose fails the job rather than pass unnoticed ($OCIO, set for a whole session, does not).
  if (options.working_space.empty() && !options.ocio_config.empty())
    load_colour_module("--ocio-config needs").check_config(find_colour_config(options.ocio_config));
  if (options.working_space.empty()) return ws;
  const colour_config_source config = find_colour_config(options.ocio_config);
  const working_space_info info =
      load_colour_module("--working-space needs").working_space(config, options.working_space);
  ws.name = info.name;
  ws.config = config.path;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) ws.from_rec709[c][r] = info.working_from_rec709[size_t(r * 3 + c)];
  ws.primaries = working_primaries(ws.from_rec709);
  return ws;
}

std::optional<display_transform> preview_view(const render_options& options) {
  if (!user_colour_config(options.ocio_config) && options.working_space.empty() && options.display.empty() &&
      options.view.empty())
    return std::nullopt;
  return load_colour_module("a preview through OpenColorIO needs")
      .display_view(find_colour_config(options.ocio_config), options.working_space, options.display,
                    options.view);
}

void apply_working_space(scene& s, const working_space& ws, memory_budget* memory,
                         const colour_conversion_scope& scope) {
  // Linear Rec.709 named through a config: tagged, but nothing to convert (and textures keep
  // their bytes rather than take an sRGB round trip).
  if (!ws.converts() || ws.from_rec709 == dmat3(1.0)) return;
  const uint64_t grown = convert_scene_colours(s, mat3(ws.from_rec709), scope);
  charge_memory(memory, grown, s.source, "colour textures converted to the working space (float texels)");
}

}  // namespace kiln
