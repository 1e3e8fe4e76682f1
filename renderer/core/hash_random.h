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

// Point i of the first two dimensions of Sobol's sequence, a (0, 2)-sequence: any 2^k consecutive
// points from a multiple of 2^k fall one in each of the 2^k elementary intervals of every shape.
// Each coordinate is XORed with a scramble (random digit scrambling), which keeps that property and
// decorrelates pixels that use different scrambles. In [0, 1).
inline void sobol_2d(uint32_t i, uint32_t scramble_x, uint32_t scramble_y, float& x, float& y) {
  uint32_t first = 0, second = 0;
  for (uint32_t v = 1u << 31, bits = i, k = 0; bits; bits >>= 1, ++k) {
    if (bits & 1u) {
      first ^= 1u << (31 - k);  // van der Corput: i's bits reversed
      second ^= v;
    }
    v ^= v >> 1;
  }
  x = float((first ^ scramble_x) >> 8) * (1.0f / 16777216.0f);
  y = float((second ^ scramble_y) >> 8) * (1.0f / 16777216.0f);
}

}  // namespace kiln
