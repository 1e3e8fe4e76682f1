// Per-pixel sample positions that depend only on (pixel, sample index): the reason the image is
// bit-identical for any thread count and tile order. Depends on core only.
#pragma once

#include <cstdint>

#include "core/hash_random.h"
#include "core/math.h"

namespace kiln {

// Offset of sample s (of spp) inside pixel (x, y), each coordinate in [0, 1).
// One sample sits at the pixel centre. Otherwise the pixel is split into n×m strata
// (n = ceil(sqrt(spp)) columns, enough rows for spp) visited in order, each jittered.
inline vec2 sample_offset(uint32_t x, uint32_t y, uint32_t s, uint32_t spp) {
  if (spp <= 1) return vec2(0.5f);
  uint32_t columns = 1;
  while (columns * columns < spp) ++columns;
  uint32_t rows = (spp + columns - 1) / columns;
  uint32_t cx = s % columns;
  uint32_t cy = s / columns;
  uint32_t pixel = hash_u32(x * 0x9E3779B1U + hash_u32(y));
  float jx = hash_to_unit(pixel, s, 0x68E31DA4U);
  float jy = hash_to_unit(pixel, s, 0xB5297A4DU);
  return vec2((cx + jx) / float(columns), (cy + jy) / float(rows));
}

// Offset of sample s inside pixel (x, y) drawn independently and uniformly, without strata: the
// baseline stratification is measured against (`--sampler random`). Also a function of
// (pixel, sample) alone.
inline vec2 random_sample_offset(uint32_t x, uint32_t y, uint32_t s) {
  uint32_t pixel = hash_u32(x * 0x9E3779B1U + hash_u32(y));
  return vec2(hash_to_unit(pixel, s, 0x1B873593U), hash_to_unit(pixel, s, 0xCC9E2D51U));
}

// Index i of [0, n) shuffled by a permutation that `seed` picks: a bijection on the next power of
// two above n (xor, odd multiplies and xor-shifts are each invertible there), walked until it lands
// below n, which it does because the walk follows i's own cycle.
inline uint32_t permuted_index(uint32_t i, uint32_t n, uint32_t seed) {
  uint32_t bits = 1;
  while ((1u << bits) < n) ++bits;
  const uint32_t mask = (1u << bits) - 1u;
  do {
    i ^= seed & mask;
    i = (i * 0x9E3779B1U) & mask;
    i ^= i >> (bits / 2 + 1);
    i = (i * 0x85EBCA6BU) & mask;
    i ^= i >> (bits / 2 + 1);
  } while (i >= n);
  return i;
}

// When in the shutter sample s of pixel (x, y) is traced (motion blur), in [0, 1). Stratified: the
// pixel's spp samples take the spp intervals of the shutter in an order each pixel shuffles (its
// own, so time does not follow where in the pixel a sample lies), each jittered. The random sampler
// draws it uniformly. A function of (pixel, sample) alone, like the offsets.
inline float sample_time(bool random, uint32_t x, uint32_t y, uint32_t s, uint32_t spp) {
  const uint32_t pixel = hash_u32(x * 0x9E3779B1U + hash_u32(y));
  const float jitter = hash_to_unit(pixel, s, 0x2545F491U);
  if (random || spp <= 1) return jitter;
  return (float(permuted_index(s % spp, spp, hash_u32(pixel ^ 0x94D049BBU))) + jitter) / float(spp);
}

// The offset of sample s of a pixel under the chosen sampler: random, or stratified into spp.
inline vec2 pixel_sample_offset(bool random, uint32_t x, uint32_t y, uint32_t s, uint32_t spp) {
  return random ? random_sample_offset(x, y, s) : sample_offset(x, y, s, spp);
}

}  // namespace kiln
