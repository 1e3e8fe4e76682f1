#include "app/stitch_command.h"

#include <CLI/CLI.hpp>

#include "io/exr/exr_reader.h"
#include "io/exr/exr_stitch.h"
#include "io/exr/exr_writer.h"

namespace kiln {

void add_stitch_options(CLI::App& app, stitch_options& o) {
  app.add_option("output", o.output, "Full-frame OpenEXR image to write")->required();
  app.add_option("inputs", o.inputs,
                 "Region EXRs with one display window and channel list that together cover it without "
                 "overlap")
      ->required()
      ->check(CLI::ExistingFile);
}

void run_stitch(const stitch_options& options) {
  check_output_writable(options.output);  // before reading, which may take long for big frames
  std::vector<exr_image> regions;
  for (const std::string& path : options.inputs) regions.push_back(read_exr(path));
  write_exr(options.output, stitch_regions(options.inputs, regions));
}

}  // namespace kiln
