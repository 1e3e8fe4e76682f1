// How kiln stores an EXR: the sample format of each colour-like layer, the compression codec,
// scanlines or tiles, and one part or one part per layer. Plain settings and the codec facts the
// CLI and the writer share; knows no OpenImageIO. Depends on the standard library only.
#pragma once

#include <string>
#include <vector>

namespace kiln {

enum class sample_format { half, float32 };

// The layers whose sample format may be chosen: values a compositor views or filters, for which
// half's 11-bit mantissa is enough. Z, P and the ids (data layers) are always 32-bit float. uv is
// float by default: half resolves 1/2048 at u = 1 and 1/1024 past it, too coarse for an STMap of a
// 2K plate or for UDIM tiles (u up to 10).
struct layer_formats {
  sample_format beauty = sample_format::half;           // R G B A
  sample_format normal = sample_format::half;           // N.X N.Y N.Z
  sample_format albedo = sample_format::half;           // albedo.R albedo.G albedo.B
  sample_format uv = sample_format::float32;            // uv.U uv.V
  sample_format direct = sample_format::half;           // direct.R direct.G direct.B
  sample_format reflection = sample_format::half;       // reflection.R ...
  sample_format refraction = sample_format::half;       // refraction.R ...
  sample_format light_groups = sample_format::half;     // lightgroup_<name>.R ... (every group)
  sample_format albedo_filtered = sample_format::half;  // albedo_filtered.R ...
  sample_format normal_filtered = sample_format::half;  // N_filtered.X ...
  sample_format diffuse = sample_format::half;          // diffuse.R ...
  sample_format specular = sample_format::half;         // specular.R ...
  sample_format shadow = sample_format::half;           // shadow_<light>.A (every light)
};

// The layers kiln writes, in the order of kiln/aovs, by the name of the part each gets with
// --multipart (Nuke shows part names as layers). The writer names its layers from this table and
// the CLI's help lists it.
enum class exr_part {
  rgba,
  depth,
  normal,
  position,
  albedo,
  uv,
  id,
  forward,
  backward,
  direct,
  reflection,
  refraction,
  albedo_filtered,
  normal_filtered,
  diffuse,
  specular,
  crypto_object,
  crypto_material
};
const std::vector<std::string>& exr_part_names();  // indexed by exr_part
const std::string& exr_part_name(exr_part part);

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
