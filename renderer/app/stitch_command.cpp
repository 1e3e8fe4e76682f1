#include "app/stitch_command.h"

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "core/memory_budget.h"
#include "io/exr/exr_reader.h"
#include "io/exr/exr_stitch.h"
#include "io/exr/exr_writer.h"
#include "job/memory_limit.h"
#include "job/option_values.h"
#include "job/output_guard.h"

namespace kiln {

void add_stitch_options(CLI::App& app, stitch_options& o) {
  app.add_option("output", o.output, "Full-frame OpenEXR image to write")->required();
  app.add_option("inputs", o.inputs,
                 "Region EXRs with one display window and channel list that together cover it without "
                 "overlap")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--max-memory", o.max_memory,
                 "Memory budget for the regions and the frame (e.g. 8G); default 90% of the memory "
                 "kiln may use");
}

void run_stitch(const stitch_options& options) {
  std::vector<input_file> inputs;
  for (const std::string& path : options.inputs) inputs.push_back({path, "an input region"});
  check_output_spares_inputs(options.output, "output", index_inputs(inputs));
  check_not_symlink(options.output, "output");
  check_exr_output_name(options.output, "output", preview_hint::hide);
  check_output_writable(options.output);  // before reading, which may take long for big frames
  // Every region and the frame are held at once: charged before each is made, so a frame too big
  // for memory is refused naming its size instead of ending in "out of memory".
  memory_budget budget(options.max_memory.empty() ? default_memory_budget()
                                                  : parse_memory_size(options.max_memory, "--max-memory"));
  std::vector<exr_image> regions;
  for (const std::string& path : options.inputs) regions.push_back(read_exr(path, &budget));
  exr_image frame = stitch_regions(options.inputs, regions, &budget);
  // Regions of one frame share its inputs and every setting but the region; kiln's own regions say
  // so in their headers, and those that disagree are refused rather than joined into a frame that
  // no render could make.
  const char* same[2] = {"kiln/input_hash", "kiln/frame_settings_hash"};
  for (size_t k = 1; k < regions.size(); ++k)
    for (const char* name : same)
      if (exr_string_attribute(regions[k], name) != exr_string_attribute(regions[0], name))
        throw input_error(
            options.inputs[k], name,
            "rendered from other inputs or settings than " + options.inputs[0] + " (" + name + " differs)");
  // The stitched frame records the settings hash of the full-frame render it equals, so
  // `kiln batch --resume` sees it as that render's output.
  const std::string frame_hash = exr_string_attribute(regions[0], "kiln/frame_settings_hash");
  if (!frame_hash.empty()) set_exr_attribute(frame, "kiln/settings_hash", frame_hash);
  write_exr(options.output, frame);
}

}  // namespace kiln
