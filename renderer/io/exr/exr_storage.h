// How kiln stores an EXR: the sample format of each colour-like layer, the compression codec,
// scanlines or tiles, and one part or one part per layer. Plain settings and the codec facts the
// CLI and the writer share; knows no OpenImageIO. Depends on render/aov_table.h only.
#pragma once

#include <string>
#include <vector>

#include "render/aov_table.h"

namespace kiln {

enum class sample_format { half, float32 };

// The sample format of each AOV's layers, by aov: half by default for the colour layers that take it
// (render/aov_table.h's half_by_default: half's 11-bit mantissa is enough for values a compositor
// views or filters), float for the rest. Data layers (Z, P, id, motion, Cryptomatte) are always
// 32-bit float whatever is set here. uv is float by default: half resolves 1/2048 at u = 1 and
// 1/1024 past it, too coarse for an STMap of a 2K plate or for UDIM tiles (u up to 10).
struct layer_formats {
  sample_format of[aov_count];

  layer_formats() {
    for (const aov_row& row : aov_table)
      of[int(row.id)] = row.half_by_default ? sample_format::half : sample_format::float32;
  }
  sample_format& operator[](aov a) { return of[int(a)]; }
  sample_format operator[](aov a) const { return of[int(a)]; }
};

// The parts kiln writes with --multipart for the AOVs of fixed name, in file order (render/aov_table.h's
// parts; Cryptomatte's last, as the writer puts them). Light groups and shadow mattes add one part
// each, named at run time.
const std::vector<std::string>& exr_part_names();

struct exr_settings {
  layer_formats formats;
  std::string compression = "zip";  // one of exr_compression_names()
  // 0: the codec's default; zip and zips take 1-9 (zlib level), dwaa and dwab a positive
  // dwaCompressionLevel (OpenEXR's default is 45).
  int compression_level = 0;
  int tile_size = 0;       // 0: scanlines; N: tiled with N×N tiles
  bool multipart = false;  // one part per layer instead of one part with every channel
};

// none, rle, zips, zip, piz, pxr24, b44, b44a, dwaa, dwab: what OpenEXR 3.1 offers.
const std::vector<std::string>& exr_compression_names();

// pxr24 (float rounded to 24 bits), b44 and b44a (half in 4×4 blocks) and dwaa and dwab (DCT)
// change values; the others reproduce every bit.
bool is_lossy_compression(const std::string& name);

// Whether compression_level means something for the codec: zip/zips and dwaa/dwab.
bool compression_takes_level(const std::string& name);

}  // namespace kiln
