#include "job/deep_output.h"

#include "core/error.h"
#include "io/exr/exr_writer.h"
#include "job/output_guard.h"
#include "job/render_job.h"

namespace kiln {

std::string deep_output_path(const std::string& output) {
  const size_t dot = output.rfind('.');
  const size_t slash = output.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return output + ".deep.exr";
  return output.substr(0, dot) + ".deep" + output.substr(dot);
}

void check_deep_job(const render_options& options, const shared_output_checks* shared) {
  if (!options.deep) return;
  if (options.output.empty()) throw input_error("", "--deep", "the deep file goes beside -o; give -o");
  const std::string path = deep_output_path(options.output);
  check_output_spares_inputs(path, "--deep",
                             shared ? shared->inputs : index_inputs(render_input_files(options)));
  check_not_symlink(path, "--deep");
  if (!options.preview.empty() && same_file(options.preview, path))
    throw input_error("", "--preview " + options.preview,
                      "the preview is the same file as the deep EXR " + path);
  check_output_writable(path, !shared || !shared->folders_probed);
  check_deep_path(make_render_settings(options), !options.crop && options.band_count <= 0);
}

}  // namespace kiln
