// A glTF asset loaded once and rendered many times: kiln.Scene, the frames of --frames and
// run_job's single render all go through it. The file is read, parsed and validated once; each
// render poses it at its own time, chooses its view and lighting, and updates the backend in place
// when it can. A render is the image run_job makes from the same options, pixel for pixel.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>

#include "job/asset_info.h"
#include "job/render_job.h"
#include "job/render_sequence.h"

namespace kiln {

// The first option (its option-table name, or "input") whose value differs between two sets of
// options and changes what loading makes: the asset, --scene, --variant, --animation, the working
// space and its config, the loader's limits, --allow-outside-files, --max-memory; "" when none.
std::string changed_load_option(const render_options& loaded, const render_options& wanted);

class loaded_scene {
 public:
  // Loads job.options.input under job's cancel flag and time limit. Throws kiln::error as run_job.
  explicit loaded_scene(const render_job& job);
  // The same step inside a run_stoppable call of the caller's (run_job: one time limit for loading
  // and rendering), under the options given.
  loaded_scene(const render_job& job, const render_options& options, const std::atomic<bool>* stop,
               const char*& stage);
  ~loaded_scene();
  loaded_scene(const loaded_scene&) = delete;
  loaded_scene& operator=(const loaded_scene&) = delete;

  // The options it was loaded with.
  const render_options& options() const;

  // Renders job.options after check_job. Options that change what is loaded (changed_load_option)
  // load the asset anew for this render alone, as run_job would; the loaded scene stays as it
  // was. Renders from several threads run one at a time. Throws kiln::error as run_job.
  render_job_result render(const render_job& job);

  // One render inside the caller's run_stoppable call, its options checked already and loading the
  // asset as it was loaded. report (may be null) receives the timings.
  render_job_result render(const render_job& job, const render_options& options,
                           const std::atomic<bool>* stop, const char*& stage, frame_report* report);

  // Renders the frames of one shot from now on (run_sequence): the lighting's notes are given once,
  // and every pose takes over what the last one built, also in a working space.
  void render_as_sequence();

  // What kiln info says of the asset under job.options (job/asset_info.h), from the kept parse and
  // posed as a render would pose it. Throws kiln::error as describe_asset.
  asset_info describe(const render_job& job);

 private:
  // Poses the scene for options into the prepared scene; true when it took over the last pose.
  bool pose(const render_job& job, const render_options& options, const std::atomic<bool>* stop,
            const char*& stage, frame_report& timings);
  bool pose_scene(const render_job& job, const render_options& options, const std::atomic<bool>* stop,
                  const char*& stage, frame_report& timings);
  void load(const render_job& job, const render_options& options, const std::atomic<bool>* stop,
            const char*& stage);

  struct state;
  std::unique_ptr<state> state_;
  std::mutex rendering_;  // one render at a time: each poses the one scene
};

}  // namespace kiln
