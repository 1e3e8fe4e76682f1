// MurmurHash3_x86_32 (Austin Appleby's public-domain reference, MurmurHash3.cpp), the hash the
// Cryptomatte specification names for its ids. Depends on nothing.
#pragma once

#include <cstdint>
#include <string_view>

namespace kiln {

// The 32-bit x86 variant of MurmurHash3 of the bytes of key (little-endian blocks, as the
// reference reads them on x86).
uint32_t murmur3_x86_32(std::string_view key, uint32_t seed = 0);

}  // namespace kiln
