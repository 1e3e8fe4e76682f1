#include "job/render_sequence.h"

#include <memory>

#include "job/frame_range.h"
#include "job/job_stop.h"
#include "job/loaded_scene.h"
#include "job/output_guard.h"
#include "job/render_job_steps.h"
#include "job/turntable.h"

namespace kiln {

render_options frame_options(const render_options& sequence, long long frame) {
  render_options o = sequence;
  o.frames.clear();
  o.frame = frame;
  o.output = frame_path(sequence.output, frame);
  if (!sequence.preview.empty()) o.preview = frame_path(sequence.preview, frame);
  return o;
}

bool renders_sequence(const render_options& options) {
  return !options.frames.empty() || (options.turntable > 0 && !options.frame);
}

std::vector<long long> sequence_frames(const render_options& options) {
  if (!options.frames.empty()) return frame_numbers(parse_frame_range(options.frames));
  return frame_numbers(turntable_frames(options));
}

std::vector<long long> check_sequence(const render_options& options) {
  const std::vector<long long> frames = sequence_frames(options);
  const char* sequence = options.frames.empty() ? "--turntable" : "--frames";
  if (options.time && !turntable_holds_pose(options))
    throw input_error(
        "", "--time",
        std::string("--time and ") + sequence + " both choose the time; give one of them" +
            (options.turntable > 0 ? " (--turntable-animation hold keeps the pose at --time)" : ""));
  if (options.frame)
    throw input_error("", "--frame", "--frame and --frames both choose the frame; give one of them");
  if (frames.size() > 1 && !options.output.empty()) {  // no output: a benchmark's frames
    if (!has_frame_placeholder(options.output))
      throw input_error("", "-o",
                        "'" + options.output + "' has no frame placeholder: with several frames (" +
                            sequence + "), name the output like shot.####.exr or shot.%04d.exr");
    if (!options.preview.empty() && !has_frame_placeholder(options.preview))
      throw input_error("", "--preview",
                        "'" + options.preview + "' has no frame placeholder (e.g. shot.####.png)");
  }
  // Every frame reads the same files and writes into the same folders: the first frame's check
  // finds both, the others check only their own outputs against them.
  shared_output_checks shared;
  shared.inputs = index_inputs(render_input_files(frame_options(options, frames.front())));
  for (long long frame : frames) {
    check_job(frame_options(options, frame), &shared);
    shared.folders_probed = true;
  }
  return frames;
}

namespace {

void render_frames(const render_job& job, const std::vector<long long>& frames, loaded_scene& kept,
                   const frame_handler& on_frame) {
  for (long long frame : frames) {
    const render_options options = frame_options(job.options, frame);
    frame_report report;
    report.frame = frame;
    const render_job_result result =
        run_stoppable(job, options, [&](const std::atomic<bool>* stop, const char*& stage) {
          return kept.render(job, options, stop, stage, &report);
        });
    on_frame(result, options, report);
  }
}

}  // namespace

void run_sequence(const render_job& job, const frame_handler& on_frame) {
  const std::vector<long long> frames = check_sequence(job.options);
  // Loaded once, under the first frame's options (the stop flag of a load ends with it).
  std::unique_ptr<loaded_scene> loaded;
  const render_options first_options = frame_options(job.options, frames.front());
  run_stoppable(job, first_options, [&](const std::atomic<bool>* stop, const char*& stage) {
    loaded = std::make_unique<loaded_scene>(job, first_options, stop, stage);
    return 0;
  });
  loaded->render_as_sequence();
  render_frames(job, frames, *loaded, on_frame);
}

void run_sequence(const render_job& job, loaded_scene& kept, const frame_handler& on_frame) {
  if (!changed_load_option(kept.options(), job.options).empty()) return run_sequence(job, on_frame);
  render_frames(job, check_sequence(job.options), kept, on_frame);
}

}  // namespace kiln
