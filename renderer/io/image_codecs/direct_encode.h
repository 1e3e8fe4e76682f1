// Encodes 8-bit PNG and JPEG in memory with libpng and libjpeg directly, in kiln itself, for the
// preview and the contact sheet: opening the image codecs module (OpenImageIO and its ~260
// libraries) to write one small picture cost a render 0.14-0.3 s of CPU at process start. The
// pictures are the ones the module's OpenImageIO 2.4 wrote: a JPEG byte for byte, a PNG with the
// same pixels and metadata, compressed faster. Depends on the standard library, libpng and libjpeg.
#pragma once

#include <string>
#include <vector>

namespace kiln {

// Encodes width x height pixels of `channels` 8-bit code values (3: R G B; 4: R G B and straight
// alpha; row 0 at the top) as an sRGB PNG into png. Returns "" or why libpng could not.
std::string encode_png(int width, int height, int channels, const unsigned char* codes,
                       std::vector<unsigned char>& png);

// Encodes width x height pixels of 8-bit R G B code values (row 0 at the top) as a baseline sRGB
// JPEG of quality 95 into jpeg. Returns "" or why libjpeg could not.
std::string encode_jpeg(int width, int height, const unsigned char* rgb, std::vector<unsigned char>& jpeg);

}  // namespace kiln
