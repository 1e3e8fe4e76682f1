// kiln's output layers (AOVs) in one table, in the order of kiln/aovs: each row says its --aovs
// name, the EXR part and channels it is written as, how the film keeps a pixel of it (filtered
// like the beauty, the nearest sample's, or Cryptomatte ranks), whether it is colour or data, its
// default sample format and its help. Parsing and listing --aovs, the film's buffers, its crop, the
// splat's filtered parts, the EXR writer's layers and formats and the help text all loop over it:
// a new AOV filtered like the beauty as three floats a pixel is its name in core/aov_id.h, a row
// here and the hook in shading that records it. Depends on render/aov_list.h only.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>

#include "render/aov_list.h"

namespace kiln {

// How a pixel of the AOV is made from its samples.
enum class aov_sampling : uint8_t {
  filtered,  // the samples folded with the beauty's filter weights (premultiplied like R G B)
  nearest,   // the nearest sample's value, never filtered (valid for compositing maths)
  ranks,     // Cryptomatte: ids ranked by the coverage of their samples
};

// How the film stores a pixel of the AOV.
enum class aov_shape : uint8_t {
  rgba,       // film::color
  scalar,     // film::depth
  triple,     // film::vec3_layer(id): three floats, the common case
  pair,       // film::uv
  ids,        // film::ids: three exact integers
  motion,     // film::motion: forward and backward (u, v)
  per_group,  // film::light_groups: three floats per light group, layers named at run time
  per_matte,  // film::shadow: one float per shadow matte, layers named at run time
  ranks,      // film::crypto_object / crypto_material
};

struct aov_row {
  aov id;
  const char* name;  // in --aovs, --channel-format and kiln/aovs
  // The EXR parts it is written as with --multipart (space-separated; the layer names of a single
  // part file too), and their channels, space-separated, in file order. Empty for layers named at
  // run time (light groups, shadow mattes, Cryptomatte).
  const char* parts;
  const char* channels;
  aov_shape shape;
  aov_sampling sampling;
  // Data (depth, positions, ids, motion, Cryptomatte) is always 32-bit float and never stored with
  // a lossy codec; colour layers take --float and --channel-format, and saturate at half's range.
  bool data;
  bool half_by_default;  // a colour layer's sample format without --float
  bool clamp_unit;       // a filtered mean clamped back into [0, 1] (a denoiser's albedo, mattes)
  const char* help;      // what it holds, for --aovs' help
};

// The rows, indexed by aov.
extern const aov_row aov_table[aov_count];

inline const aov_row& aov_row_of(aov a) { return aov_table[int(a)]; }

// The vec3 parts filtered beside the beauty with its weights, per sample: one per filtered AOV asked
// for, in the table's order, where light groups take one per group and the shadow mattes (the
// lights' and the environment's) are packed three to a part. light_groups counts the groups: the
// lights plus emission and environment.
inline int shadow_part_count(int light_groups) { return (std::max(light_groups - 1, 0) + 2) / 3; }
int beauty_part_count(const aov_set& a, int light_groups);

// "beauty, Z, N, ..." (with cryptomatte, the shorthand for both Cryptomatte layers).
std::string aov_name_list();

// The help of --aovs: every row's name and what it holds.
std::string aov_help();

}  // namespace kiln
