// The chunk walk both PNG decoders make before libpng sees the data (the module's and kiln's own,
// direct_decode.h), so that they refuse the same truncated files. Depends on nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace kiln {

// Walks a PNG's chunk list (length, type, data, CRC) after its 8-byte signature and returns why it
// is cut short or broken, or an empty string when every chunk fits and the list ends with IEND.
// libpng decodes the rows of a PNG cut anywhere after its image data without a complaint, and
// reports a short read inside them by longjmp (past the C++ frames of a reader that has them).
std::string png_structure_problem(const uint8_t* data, size_t size);

}  // namespace kiln
