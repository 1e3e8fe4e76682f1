// `kiln batch`: renders many assets in one process, each through the same path as `kiln render`,
// with the render options as defaults that a manifest refines per job. One failing job never
// stops the others; --resume skips outputs that are complete and up to date; a summary records
// every job's fate, also after a failure or a signal. App layer only.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/render_command.h"

namespace CLI {
class App;
}

namespace kiln {

struct batch_options {
  render_options defaults;          // every job starts from these (asset and output unset)
  std::vector<std::string> assets;  // files or glob(3) patterns
  std::string manifest;             // .json or .csv; empty: none
  std::string out_dir;
  bool resume = false;
  bool wait_for_lock = false;  // another batch holds --out-dir: wait instead of refusing
  std::string summary;         // JSON summary path; empty: none
  std::string plan;            // --plan-only: write the job plan here and render nothing
  std::string contact_sheet;   // --contact-sheet FILE.png|FILE.jpg: every job's image in a grid; empty: none
  bool plan_estimates = true;  // the plan carries each job's estimate (--no-estimates: not)
};

// What the jobs of one manifest entry (or one of its variants, or one asset argument) share.
struct batch_entry {
  std::string where;       // the manifest location, or the asset argument
  render_options options;  // input and output absolute; a sequence's keep --frames and the placeholder
  std::string error;       // non-empty: the options did not parse; its jobs fail without rendering
};

// One resolved job: its entry, and for a frame of a sequence the frame. The frames of an entry
// share it, so a frame plans in under 200 bytes instead of a copy of the render options: a
// job's own options are made when it is checked, written or rendered (batch_job_options).
struct batch_job {
  std::string name;  // unique: the output's path under --out-dir without .exr
  std::shared_ptr<const batch_entry> entry;
  std::optional<long long> frame;  // set: the options are frame_options(entry->options, *frame)
};

// The options `kiln render` would get for job (input and output absolute).
render_options batch_job_options(const batch_job& job);

// The EXR job writes, without making its options.
std::string batch_job_output(const batch_job& job);

void add_batch_options(CLI::App& app, batch_options& options);

// Expands patterns, reads the manifest, applies defaults and overrides, names the outputs.
// Throws kiln::error (input) for a malformed manifest, a pattern without matches, no jobs, or two
// jobs writing one output.
std::vector<batch_job> plan_batch(const batch_options& options);

// Parses render arguments (no asset, no -o) onto options through the same CLI11 declarations as
// `kiln render`. Throws CLI::ParseError with the parser's message.
void apply_render_arguments(render_options& options, const std::vector<std::string>& arguments);

// Runs the batch (or writes the plan). Returns the exit code: 0 every job rendered or skipped,
// 1 some failed, 128 + signal when interrupted. Throws kiln::error for bad input before any job.
int run_batch(const batch_options& options);

}  // namespace kiln
