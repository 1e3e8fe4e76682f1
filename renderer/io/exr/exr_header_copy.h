// Copies of OpenEXR headers without one attribute. OpenEXR 3.1's Header::erase takes an attribute
// out of the header without freeing it (LeakSanitizer finds every one), so kiln never erases:
// it copies every other attribute, and the codec levels (fields, not attributes), into a fresh
// header. Inside io/exr only.
#pragma once

#include <OpenEXR/ImfHeader.h>

#include <cstring>

namespace kiln {

inline Imf::Header header_without(const Imf::Header& source, const char* name) {
  Imf::Header out;
  for (auto a = source.begin(); a != source.end(); ++a)
    if (std::strcmp(a.name(), name) != 0) out.insert(a.name(), a.attribute());
  out.zipCompressionLevel() = source.zipCompressionLevel();
  out.dwaCompressionLevel() = source.dwaCompressionLevel();
  return out;
}

}  // namespace kiln
