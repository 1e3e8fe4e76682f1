// Random numbers as pure functions of integers: what keeps every sample, and every choice a shading
// point makes, the same for any thread count and tile order. Depends on nothing.
#pragma once

#include <cstdint>

namespace kiln {

// A 32-bit integer hash with good avalanche (the "lowbias32" constants of Chris Wellons'
// hash-prospector); enough for jitter, and the same on every platform.
inline uint32_t hash_u32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

// Uniform float in [0, 1) from a hash of three integers.
inline float hash_to_unit(uint32_t a, uint32_t b, uint32_t c) {
  uint32_t h = hash_u32(a ^ hash_u32(b ^ hash_u32(c)));
  return float(h >> 8) * (1.0f / 16777216.0f);
}

}  // namespace kiln
