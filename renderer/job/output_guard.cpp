#include "job/output_guard.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "io/file/input_file.h"
#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_references.h"
#include "job/memory_limit.h"

namespace kiln {

namespace {

namespace fs = std::filesystem;

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// The path with every symlink in its existing part resolved; the absolute path when that fails.
std::string canonical_name(const std::string& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec).lexically_normal();
  const fs::path canonical = fs::weakly_canonical(absolute, ec);
  return (ec ? absolute : canonical).string();
}

}  // namespace

std::vector<input_file> render_input_files(const render_options& options, const std::atomic<bool>* cancel) {
  std::vector<input_file> files{{options.input, "the asset"}};
  // The loader's URI rule: a URI it would refuse (outside the folder, a FIFO) is refused here too.
  gltf_load_options rules;
  rules.allow_files_outside_folder = options.allow_outside_files;
  rules.limits.max_json_bytes = options.limits.max_json_bytes;
  rules.cancel = cancel;
  // JSON whose parse would pass the job's memory budget is not parsed here: the loader refuses it.
  memory_budget budget(options.max_memory ? options.max_memory : default_memory_budget());
  rules.memory = &budget;
  // A missing or unreadable asset names nothing: its render reports it (a batch fails that job only).
  if (options.in_memory)
    files.clear();  // an asset in memory reads no file of its own
  else if (input_file_missing(options.input) ||
           !input_file_problem(options.input, max_gltf_file_bytes).empty())
    return files;
  else
    for (const std::string& file : gltf_referenced_files(options.input, rules))
      files.push_back({file, "a buffer or image file of " + options.input});
  if (!options.environment.empty()) files.push_back({options.environment, "the --environment map"});
  return files;
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {
  }, sb{};
  const bool a_exists = ::stat(a.c_str(), &sa) == 0, b_exists = ::stat(b.c_str(), &sb) == 0;
  if (a_exists && b_exists) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (a_exists != b_exists) return false;
  return canonical_name(a) == canonical_name(b);
}

input_index index_inputs(const std::vector<input_file>& inputs) {
  input_index index;
  for (const input_file& input : inputs) {
    struct stat s {};
    if (::stat(input.path.c_str(), &s) == 0)
      index.by_inode.emplace(std::make_pair(s.st_dev, s.st_ino), input);
    else
      index.by_name.emplace(canonical_name(input.path), input);
  }
  return index;
}

void check_exr_output_name(const std::string& path, const std::string& option, preview_hint hint) {
  const std::string ext = lower_extension(path);
  if (ext == ".exr") return;
  if (hint == preview_hint::show && (ext == ".png" || ext == ".jpg" || ext == ".jpeg"))
    throw input_error("", option + " " + path,
                      "kiln writes OpenEXR only, so the output must end in .exr; for an 8-bit image of the "
                      "beauty, render to an .exr and add --preview " +
                          path);
  throw input_error("", option + " " + path, "kiln writes OpenEXR only, so the output must end in .exr");
}

void check_not_symlink(const std::string& path, const std::string& option) {
  std::error_code ec;
  if (!fs::is_symlink(fs::symlink_status(path, ec))) return;
  const std::string target = fs::read_symlink(path, ec).string();
  throw input_error("", option + " " + path,
                    "the output is a symbolic link (to " + target +
                        "); kiln renames a finished file into place, which would replace the link by a "
                        "regular file and leave what it points to as it was: give the target's own path");
}

void check_output_spares_inputs(const std::string& output, const std::string& option,
                                const input_index& inputs) {
  // An existing output can only be an existing input, a missing one only a missing input.
  struct stat s {};
  const input_file* hit = nullptr;
  if (::stat(output.c_str(), &s) == 0) {
    auto it = inputs.by_inode.find({s.st_dev, s.st_ino});
    if (it != inputs.by_inode.end()) hit = &it->second;
  } else {
    auto it = inputs.by_name.find(canonical_name(output));
    if (it != inputs.by_name.end()) hit = &it->second;
  }
  if (hit)
    throw input_error(
        "", option + " " + output,
        "the output is " + hit->role + " (" + hit->path + "); writing it would destroy an input");
}

void check_render_outputs(const render_options& options, const shared_output_checks* shared) {
  // The most telling reason first: "-o a.gltf" is the asset before it is a name without .exr.
  const input_index inputs = shared ? input_index{} : index_inputs(render_input_files(options));
  const input_index& index = shared ? shared->inputs : inputs;
  check_output_spares_inputs(options.output, "-o", index);
  if (!options.preview.empty()) check_output_spares_inputs(options.preview, "--preview", index);
  check_not_symlink(options.output, "-o");
  if (!options.preview.empty()) check_not_symlink(options.preview, "--preview");
  check_exr_output_name(options.output, "-o", preview_hint::show);
  if (!options.preview.empty() && same_file(options.preview, options.output))
    throw input_error("", "--preview " + options.preview,
                      "the preview is the same file as the -o output " + options.output);
}

}  // namespace kiln
