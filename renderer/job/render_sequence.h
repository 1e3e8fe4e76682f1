// The frames of a shot in one process (--frames): the asset is read and parsed once, each frame
// poses it again (gltf_sequence: only the deformed meshes are built anew) and the backend is
// updated in place (Embree moves its instances and refits the deformed meshes) instead of being
// built again. Each frame is the render `kiln render --frame N -o FRAME_OUTPUT` would make, pixel
// for pixel, with its own EXR header and settings hash.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "job/render_job.h"

namespace kiln {

// Whether the options render a sequence: --frames, or --turntable without --frame (all its frames).
bool renders_sequence(const render_options& options);

// The sequence's frames: those --frames names, else the turntable's (job/turntable.h). Throws
// kiln::error (input) for a bad range.
std::vector<long long> sequence_frames(const render_options& options);

// The options of one frame of a sequence: --frame N, the outputs with the frame placeholder
// filled in, and no --frames.
render_options frame_options(const render_options& sequence, long long frame);

// The frames of the sequence, after checking its options: no --time (except to hold a turntable's
// pose) or --frame beside them, a frame placeholder in -o (and --preview) when there is more than one
// frame, and every frame's own checks (check_job). Throws kiln::error (input or io).
std::vector<long long> check_sequence(const render_options& options);

// How a sequence's frame was made: rendered with a backend built for it, or with the last frame's
// updated in place, and with the last frame's texture pyramids and environment tables or new ones.
struct frame_report {
  long long frame = 0;
  bool backend_updated = false;
  bool textures_kept = false;
  bool environment_kept = false;
  double pose_seconds = 0.0;    // posing the scene (and for the first frame, loading it)
  double update_seconds = 0.0;  // building or updating the backend
};

// What receives each frame of a sequence as it finishes (and writes it).
using frame_handler =
    std::function<void(const render_job_result&, const render_options&, const frame_report&)>;

// Renders every frame of the sequence (sequence_frames) in order and hands each to on_frame (which writes
// it) before the next starts; an error stops the sequence there (earlier frames stay written).
// Throws like run_job; --time-limit applies to each frame.
void run_sequence(const render_job& job, const frame_handler& on_frame);

// The same from a scene loaded already (kiln.Scene): each frame is a render of it
// (job/loaded_scene.h). Options that change what is loaded load the asset anew, as above.
class loaded_scene;
void run_sequence(const render_job& job, loaded_scene& kept, const frame_handler& on_frame);

}  // namespace kiln
