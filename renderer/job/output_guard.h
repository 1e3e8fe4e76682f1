// Output paths that would destroy input: checks every command that writes images runs before any
// work, so that no output (EXR, preview, stitched frame, batch job) can replace a file the run
// reads, a symbolic link, or a file under a name that hides its format.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "job/render_options.h"

namespace kiln {

// A file a command reads, with what it is for the message ("the asset", "--environment").
struct input_file {
  std::string path;
  std::string role;
};

// Every file a render reads: the asset, each buffer and image file its URIs name, the environment
// map.
std::vector<input_file> render_input_files(const render_options& options,
                                           const std::atomic<bool>* cancel = nullptr);

// Whether two paths name one file: the same device and inode when both exist (so hard links and
// symlinks count), else the same canonical path.
bool same_file(const std::string& a, const std::string& b);

// Throws kiln::error (input) naming option unless path ends in .exr (any case); for a PNG or JPEG
// name a render's message points to --preview.
enum class preview_hint { show, hide };
void check_exr_output_name(const std::string& path, const std::string& option, preview_hint hint);

// Throws kiln::error (input) when path is a symbolic link, dangling or not. kiln writes a temporary
// file and renames it over the output, which would replace the link itself by a regular file and
// leave the file it points to stale; refusing is the one answer that surprises nobody.
void check_not_symlink(const std::string& path, const std::string& option);

// Inputs looked up by identity: existing files by device and inode, missing ones by canonical path.
struct input_index {
  std::map<std::pair<dev_t, ino_t>, input_file> by_inode;
  std::map<std::string, input_file> by_name;
};
input_index index_inputs(const std::vector<input_file>& inputs);

// Throws kiln::error (input) when output is the same file (as same_file decides) as any input.
void check_output_spares_inputs(const std::string& output, const std::string& option,
                                const input_index& inputs);

// What the frames of one sequence share, found once for all of them: the files they read, and
// whether their output folders were probed (every frame writes into the first frame's folders).
// Checking a million frames then neither parses the asset nor creates a file a million times.
struct shared_output_checks {
  input_index inputs;  // index_inputs(render_input_files(options))
  bool folders_probed = false;
};

// Everything above for one render's -o and --preview (also against each other); shared, when
// given, holds the inputs (else they are read here).
void check_render_outputs(const render_options& options, const shared_output_checks* shared = nullptr);

}  // namespace kiln
