// The environment as a light: directions drawn in proportion to the radiance it sends (a constant
// environment uniformly over the sphere; a map by its luminance × solid angle, as a 2D
// piecewise-constant distribution over the equirectangular image: a row by its marginal, then a
// texel in the row, then a point in the texel), and the density of any direction under that
// drawing, for multiple importance sampling against the BSDF. Depends on scene only.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace kiln {

struct environment_light {
  bool lights = false;  // some direction sends radiance: shading samples it
  bool uniform = true;  // a constant colour (no map)
  int width = 0;        // the map's texels, when not uniform
  int height = 0;
  float rotation = 0.0f;  // the map's turn about +Y (environment::rotation)
  // The density over the map's [0,1]² (u, v) of each texel, row-major: its weight / mean weight.
  std::vector<float> texel_density;
  std::vector<float> row_cdf;     // height + 1 entries, from 0 to 1
  std::vector<float> column_cdf;  // per row, width + 1 entries from 0 to 1
  // Guide tables (Chen and Asau's index tables) over each CDF: entry b of a CDF's table is the
  // interval that u = b / G falls in, G a power of two (so b / G is exact); a draw then searches
  // only the intervals between two neighbouring entries, and finds the interval the whole CDF's
  // binary search finds, in a step or two instead of log2(width) cache misses.
  int row_guide_size = 0;              // G of the row CDF
  int column_guide_size = 0;           // G of each row's CDF
  std::vector<uint32_t> row_guide;     // row_guide_size + 1 entries
  std::vector<uint32_t> column_guide;  // per row, column_guide_size + 1 entries
  texel_buffer source;                 // the map's, when the tables were made (environment_light_fits)
};

// The bytes make_environment_light(s) allocates: about three words a texel of a map (its density, its
// row's CDF and guide table), for the job's memory budget.
uint64_t environment_light_bytes(const scene& s);

// The environment light of s's environment (lights false when it is black everywhere).
environment_light make_environment_light(const scene& s);

// Whether e's tables are the ones make_environment_light(s) would make: e was made from a map,
// and s's map holds the same texel buffer (texel_buffer: moved, not read again)
// and lights the scene (intensity above 0). A loaded scene keeps the tables across its renders
// (job/loaded_scene.cpp) and drops them whenever it reads its map again, since a freed buffer's
// address can come back. The map's rotation turns directions, not the tables: the caller sets e's
// from s.
bool environment_light_fits(const environment_light& e, const scene& s);

// A direction drawn from e (lights) by two uniform numbers in [0, 1), and its density per
// steradian (0 for a direction that cannot be drawn, such as a map's pole).
struct environment_sample {
  vec3 direction{0.0f, 1.0f, 0.0f};
  float pdf = 0.0f;
  vec2 uv{0.0f};  // with a map: the coordinates drawn, so its radiance needs no trigonometry
};
environment_sample sample_environment(const environment_light& e, const vec2& u);

// out[i] = sample_environment(e, u[i]) for each of count draws, the same bits, with the draws'
// memory reads overlapped: a shading point's pairs draw together.
void sample_environment_run(const environment_light& e, const vec2* u, int count, environment_sample* out);

// The density per steradian with which sample_environment draws the unit direction d.
float environment_pdf(const environment_light& e, const vec3& d);

// The same for a direction d whose map coordinates uv (environment_uv of d) the caller has.
float environment_pdf_at(const environment_light& e, const vec3& d, const vec2& uv);

// The world direction of equirectangular coordinates (u, v) for a map turned by rotation: the
// inverse of environment.h's environment_uv.
vec3 environment_direction(const vec2& uv, float rotation_radians);

}  // namespace kiln
