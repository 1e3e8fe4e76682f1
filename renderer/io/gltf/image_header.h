// An encoded image's size read from its own header (PNG IHDR, JPEG SOF, WebP VP8/VP8L/VP8X, GIF
// logical screen, BMP info header), before any decoder runs: some decoders allocate the whole
// frame while opening a file (a progressive JPEG claiming 20000x20000 in 1 KB), so the texel limit
// must be checked first. Knows no image library. Internal to io/gltf.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace kiln::gltf_internal {

struct image_header {
  std::string format;  // "PNG", "JPEG", "WebP", "GIF", "BMP"; empty: not one of them
  uint64_t width = 0;  // 0 with a known format: the header is cut short or holds no size
  uint64_t height = 0;
};

image_header read_image_header(const uint8_t* data, size_t size);

// Why data cannot hold the h.width x h.height image its header declares, or "": a PNG's image data
// (IDAT) or a lossy WebP's VP8 data too short to decode to that size however it is coded (deflate
// expands at most 1032:1; VP8 spends over a bit on the prediction modes of each 16x16 macroblock).
// The decoders allocate the whole image before they find the data missing, so a few bytes
// declaring 16384x16384 would cost a gigabyte each. Formats that can code any size in a few bytes
// (lossless WebP, GIF, JPEG's arithmetic coding) must bring a byte of file for every 4096 bytes of
// 8-bit RGBA texels once the image passes 64 MiB: only a near-uniform image codes tighter.
std::string image_data_problem(const uint8_t* data, size_t size, const image_header& h);

}  // namespace kiln::gltf_internal
