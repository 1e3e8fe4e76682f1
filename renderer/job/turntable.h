// Views framed on the asset from a chosen direction, the deliverables of asset review:
// --camera-view (front, three-quarter, top, or AZIMUTH,ELEVATION) and --turntable N (N frames
// orbiting the asset about +Y through its bounds' centre). Both frame the bounding sphere as the
// default camera does (render/view_camera.h's make_orbit_camera), so the whole asset is in view from
// every direction. Depends on the job's options only.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "job/frame_range.h"
#include "job/render_options.h"

namespace kiln {

// --turntable-elevation's default: a little above the asset, as a product turntable is shot.
constexpr double default_turntable_elevation = 20.0;

// Where an orbit view looks from, in degrees: azimuth about +Y from +Z towards +X (counter-clockwise
// seen from above), elevation above the x-z plane.
struct orbit_angles {
  double azimuth = 0.0;
  double elevation = 0.0;
  std::string description;  // kiln/camera: "three-quarter view (azimuth 45, elevation 25)"
};

// --camera-view's named directions: front (azimuth 0, elevation 0), three-quarter (45, 25), top (0, 90).
std::vector<std::string> camera_view_names();

// --camera-view's text: a name or AZIMUTH,ELEVATION (elevation within ±90). Throws kiln::error
// (input, location --camera-view) for anything else.
orbit_angles parse_camera_view(const std::string& text);

// Whether the options look through an orbit view (--camera-view or --turntable).
bool uses_orbit_view(const render_options& options);

// --turntable with --turntable-animation hold: the asset keeps the pose at --time (default 0) while
// the camera turns.
bool turntable_holds_pose(const render_options& options);

// A turntable's frames: --frame-start (default 1) and the N - 1 after it.
frame_range turntable_frames(const render_options& options);

// The orbit the options view the asset from: --camera-view's, or for a turntable, frame F's at
// azimuth start + 360° · (F - first frame) / N (any F: the orbit repeats); nullopt for neither.
// Throws kiln::error (input) when an orbit meets another option that chooses the camera (--camera,
// --look-from/--look-at, each other), a --turntable-* option comes without --turntable, or a
// turntable has no --frame.
std::optional<orbit_angles> job_orbit(const render_options& options);

// A turntable frame's own checks, for run_job's (job/render_job.h's check_job): the camera options
// above, a --frame among the turntable's, no --shutter. Throws kiln::error (input).
void check_turntable_frame(const render_options& options);

// The options of the frame `offset` frames from the job's along its turntable (the neighbours of
// motion vectors); options unchanged without a turntable.
render_options turntable_neighbour(const render_options& options, long long offset);

}  // namespace kiln
