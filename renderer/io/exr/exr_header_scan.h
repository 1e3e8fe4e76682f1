// A scan of an EXR's headers before OpenEXR reads them: OpenEXR 3.1 allocates each attribute at
// the size the file declares and an offset table at the size the data window implies, so a few
// damaged bytes can ask for gigabytes. Every declared size must fit in the bytes the file has.
// Inside io/exr only; depends on the standard library.
#pragma once

#include <cstdint>
#include <string>

namespace kiln {

// "" when every header attribute of the file at path (each part's, for a multi-part file) declares
// a size within the file's remaining bytes, and each part's chunk offset table fits in the file;
// else what does not, in a few words.
std::string exr_header_sizes_problem(const std::string& path);

// The scanlines one chunk of a scanline part holds under OpenEXR's compression number (1 for none,
// RLE and ZIPS; 16 ZIP and PXR24; 32 PIZ, B44, B44A and DWAA; 256 DWAB).
int64_t exr_lines_per_chunk(int compression);

}  // namespace kiln
