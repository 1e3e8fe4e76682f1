#include "app/render_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

#include "app/interrupt.h"
#include "app/option_cli.h"
#include "app/output_lock.h"
#include "app/progress_report.h"
#include "core/error.h"
#include "job/render_sequence.h"

namespace kiln {

namespace {

void print_note(const std::string& line) { std::cerr << "kiln: " << line << '\n'; }

// The closing line: size, sampling, threads, timings and ray counts.
void print_summary(const render_job_result& result, const render_options& options) {
  const bool adaptive = options.adaptive_threshold > 0.0f;
  std::string sampling;
  for (const auto& [key, value] : result.metadata.attributes) {
    const std::string* text = std::get_if<std::string>(&value);
    if (adaptive && key == "kiln/adaptive" && text) sampling = "adaptive " + *text;
    if (!adaptive && key == "kiln/filter" && text)
      sampling = std::to_string(samples_per_pixel_of(options)) + " spp, " + *text + " filter";
  }
  const render_statistics& stats = result.stats;
  std::fprintf(stderr,
               "kiln: %dx%d, %s, %d threads: load %.3f s, build %.3f s, render %.3f s "
               "(%llu camera, %llu shadow, %llu reflection, %llu refraction rays; %llu non-finite samples "
               "discarded) -> %s\n",
               result.width, result.height, sampling.c_str(), stats.threads_used, result.load_seconds,
               result.build_seconds, stats.seconds, (unsigned long long)stats.rays.camera,
               (unsigned long long)stats.rays.shadow, (unsigned long long)stats.rays.reflection,
               (unsigned long long)stats.rays.refraction, (unsigned long long)stats.discarded_samples,
               options.output.c_str());
}

void add_asset_argument(CLI::App& app, render_options& o) {
  app.add_option("asset", o.input, "glTF 2.0 asset to render (.gltf or .glb)")->required();
}

}  // namespace

void add_view_options(CLI::App& app, render_options& o) {
  add_asset_argument(app, o);
  add_view_settings(app, o);
}

void add_view_settings(CLI::App& app, render_options& o) { add_table_options(app, o, {option_scope::view}); }

void add_image_options(CLI::App& app, render_options& o) { add_table_options(app, o, {option_scope::image}); }

void add_render_options(CLI::App& app, render_options& o) {
  add_asset_argument(app, o);
  app.add_option("-o,--output", o.output, "Output OpenEXR file")
      ->required()
      ->group(option_group_title(option_group::output));  // first in its group, the group first
  add_table_options(app, o, {option_scope::view, option_scope::image, option_scope::progress});
  // Internal: kiln batch runs each job as `kiln render ... --batch-command-line LINE` in a child
  // process; LINE is the job's own command line for the EXR header. Hidden from --help.
  app.add_option_function<std::string>(
         "--batch-command-line",
         [&o](const std::string& line) {
           o.command_line = line;
           o.batch_job = true;
           o.summary_line = false;  // the batch prints its own line per job
         },
         "")
      ->group("");
}

prepared_scene prepare_cli_scene(const render_options& options) {
  return prepare_scene(options, &interrupt_requested(), options.quiet ? nullptr : print_note);
}

namespace {

// A running batch owns its output folder; its own jobs (children) write there.
void check_outputs_unlocked(const render_options& options) {
  if (options.batch_job) return;
  check_not_in_locked_folder(options.output);
  if (!options.preview.empty()) check_not_in_locked_folder(options.preview);
}

// The job of the command line, reporting to stderr and to progress.
render_job cli_job(const render_options& options, const render_fingerprint* known,
                   render_progress& progress) {
  render_job job;
  job.options = options;
  job.cancel = &interrupt_requested();
  if (!options.quiet) job.warn = print_note;
  job.fingerprint = known;
  job.progress = &progress;
  return job;
}

// --frames, --turntable: every frame rendered and written in turn, one summary line each.
void run_render_sequence(const render_options& options, const render_fingerprint* known) {
  for (long long number : check_sequence(options)) check_outputs_unlocked(frame_options(options, number));
  render_progress progress;
  const render_job job = cli_job(options, known, progress);
  const progress_report report(progress, !options.quiet, options.progress_interval);
  run_sequence(
      job, [&](const render_job_result& result, const render_options& frame, const frame_report& made) {
        write_job_outputs(result, frame, &interrupt_requested());
        if (options.quiet || !options.summary_line) return;
        const char* kept = made.textures_kept && made.environment_kept
                               ? "; kept: texture pyramids, environment tables"
                           : made.textures_kept    ? "; kept: texture pyramids"
                           : made.environment_kept ? "; kept: environment tables"
                                                   : "";
        std::fprintf(stderr, "kiln: frame %lld: %s%s\n", made.frame,
                     made.backend_updated ? "instances moved and deformed meshes refitted" : "backend built",
                     kept);
        print_summary(result, frame);
      });
}

}  // namespace

void run_render(const render_options& options, const render_fingerprint* known) {
  for (const std::string& line : job_option_warnings(options)) print_note(line);  // even with -q
  if (renders_sequence(options)) return run_render_sequence(options, known);
  check_outputs_unlocked(options);
  render_progress progress;
  const render_job job = cli_job(options, known, progress);
  render_job_result result;
  {
    const progress_report report(progress, !options.quiet, options.progress_interval);
    result = run_job(job);
  }
  write_job_outputs(result, options, &interrupt_requested());
  if (!options.quiet && options.summary_line) print_summary(result, options);
}

}  // namespace kiln
