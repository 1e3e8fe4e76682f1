// The deep EXR of a render job (--deep): where it goes, the checks before rendering, and the deep
// image with the memory charged for it. The flat EXR's safety rules apply to it as well.
#pragma once

#include <memory>
#include <string>

#include "core/memory_budget.h"
#include "job/render_options.h"
#include "render/deep_pixel.h"

namespace kiln {

// The deep file beside output: "shot.0001.exr" -> "shot.0001.deep.exr" (output ends in .exr, which
// check_exr_output_name makes sure of; anything else gets ".deep.exr" appended).
std::string deep_output_path(const std::string& output);

// With --deep: the deep file is safe to write (never an input, never through a symlink, writable,
// not -o or the preview) and the options take the path deep output supports (whole frame,
// stratified samples, a box filter inside the pixel, no visible background). Throws kiln::error
// (input or io) before anything loads. Without --deep it does nothing.
// shared: as check_render_outputs's.
struct shared_output_checks;
void check_deep_job(const render_options& options, const shared_output_checks* shared = nullptr);

// A render's deep image and the part of the job's memory budget it holds; the charge is given
// back when the deep image goes (after it is written). The budget outlives both.
struct deep_output {
  std::shared_ptr<memory_budget> budget;
  memory_charge charge;
  deep_image image;
  explicit deep_output(std::shared_ptr<memory_budget> b) : budget(std::move(b)), charge(budget.get()) {}
};

}  // namespace kiln
