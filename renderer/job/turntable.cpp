#include "job/turntable.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "job/option_values.h"

namespace kiln {

namespace {

struct named_view {
  const char* name;
  double azimuth, elevation;
};

// Three-quarter: the front and one side at once, seen a little from above, as product shots are.
constexpr named_view named_views[] = {{"front", 0.0, 0.0}, {"three-quarter", 45.0, 25.0}, {"top", 0.0, 90.0}};

// "azimuth 45, elevation 25": the angles as the EXR's kiln/camera gives them.
std::string angles_text(double azimuth, double elevation) {
  char text[96];
  std::snprintf(text, sizeof text, "azimuth %.6g, elevation %.6g", azimuth, elevation);
  return text;
}

// The options that choose the camera some other way, refused beside an orbit view.
void check_single_view(const render_options& o, const std::string& option) {
  if (o.turntable > 0 && !o.camera_view.empty())
    throw input_error("", "--camera-view",
                      "--camera-view and --turntable both choose the view; give one of them");
  if (o.look_from || o.look_at)
    throw input_error("", option, "frames the asset itself; drop --look-from and --look-at");
  if (!o.camera.empty()) throw input_error("", option, "frames the asset itself; drop --camera");
}

}  // namespace

std::vector<std::string> camera_view_names() {
  std::vector<std::string> names;
  for (const named_view& v : named_views) names.emplace_back(v.name);
  return names;
}

orbit_angles parse_camera_view(const std::string& text) {
  for (const named_view& v : named_views)
    if (text == v.name)
      return {v.azimuth, v.elevation,
              std::string(v.name) + " view (" + angles_text(v.azimuth, v.elevation) + ")"};
  const size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos)
    throw input_error(
        "", "--camera-view",
        "expected front, three-quarter, top or AZIMUTH,ELEVATION in degrees, got '" + text + "'");
  orbit_angles a;
  a.azimuth = parse_number(text.substr(0, comma), "--camera-view", -1e6, 1e6);
  a.elevation = parse_number(text.substr(comma + 1), "--camera-view", -90.0, 90.0);
  a.description = "camera view (" + angles_text(a.azimuth, a.elevation) + ")";
  return a;
}

bool uses_orbit_view(const render_options& options) {
  return options.turntable > 0 || !options.camera_view.empty();
}

bool turntable_holds_pose(const render_options& options) {
  return options.turntable > 0 && options.turntable_animation.value_or("play") == "hold";
}

frame_range turntable_frames(const render_options& options) {
  frame_range r;
  r.first = options.frame_start.value_or(1);
  r.last = r.first + std::max(options.turntable, 1LL) - 1;
  if (r.last > max_frame_number)
    throw input_error("", "--turntable",
                      "its last frame " + std::to_string(r.last) + " passes the largest frame number, " +
                          std::to_string(max_frame_number) + " (lower --frame-start)");
  return r;
}

std::optional<orbit_angles> job_orbit(const render_options& o) {
  if (o.turntable <= 0) {
    const std::pair<bool, const char*> turntable_only[] = {
        {o.turntable_elevation.has_value(), "--turntable-elevation"},
        {o.turntable_start.has_value(), "--turntable-start"},
        {o.turntable_animation.has_value(), "--turntable-animation"}};
    for (const auto& [given, name] : turntable_only)
      if (given) throw input_error("", name, "only applies to --turntable; give --turntable N");
    if (o.camera_view.empty()) return std::nullopt;
    check_single_view(o, "--camera-view");
    return parse_camera_view(o.camera_view);
  }
  check_single_view(o, "--turntable");
  if (!o.frame)
    throw input_error(
        "", "--turntable",
        "one frame of a turntable needs --frame N (kiln render without --frame renders them all)");
  const frame_range frames = turntable_frames(o);
  orbit_angles a;
  a.elevation = o.turntable_elevation.value_or(default_turntable_elevation);
  a.azimuth = o.turntable_start.value_or(0.0) + 360.0 * double(*o.frame - frames.first) / double(o.turntable);
  a.description = "turntable frame " + std::to_string(*o.frame - frames.first + 1) + " of " +
                  std::to_string(o.turntable) + " (" + angles_text(a.azimuth, a.elevation) + ")";
  return a;
}

void check_turntable_frame(const render_options& options) {
  job_orbit(options);
  if (options.turntable <= 0) return;
  const frame_range frames = turntable_frames(options);
  if (*options.frame < frames.first || *options.frame > frames.last)
    throw input_error("", "--frame",
                      "frame " + std::to_string(*options.frame) + " is not one of the turntable's frames " +
                          std::to_string(frames.first) + "-" + std::to_string(frames.last));
  if (options.shutter)
    throw input_error(
        "", "--shutter",
        "a turntable's camera does not blur as it turns; render the turntable without --shutter");
}

render_options turntable_neighbour(const render_options& options, long long offset) {
  render_options o = options;
  if (o.turntable > 0 && o.frame) *o.frame += offset;
  return o;
}

}  // namespace kiln
