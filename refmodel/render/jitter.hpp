// render.jitter (docs/leaping.md): the per-pixel start offset every engine
// computes, bit for bit the same (the hls kernels include this header: plain
// integer arithmetic, synthesizable as written; C++14 like the kernels).
#pragma once

#include <cstdint>

namespace voxcast {
namespace ref {

// The per-pixel hash (lowbias32, C. Wellons' "hash prospector" integer hash):
// px < 2^13 and py < 2^13 (render.width/height <= 8192) are packed into the
// input word. Pure integer arithmetic: synthesizable as written.
constexpr std::uint32_t pixel_hash(std::uint32_t px, std::uint32_t py) {
  std::uint32_t x = (py << 13) ^ px ^ 0x5bd1e995u;
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// The jitter of pixel (px, py) as an integer J in [0, 2^bits): the start moves
// J·2^-bits of a step. bits <= 32.
constexpr std::uint32_t jitter_raw(int px, int py, int bits) {
  if (bits <= 0) return 0;
  const std::uint32_t h = pixel_hash(static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py));
  return bits >= 32 ? h : h >> (32 - bits);
}

}  // namespace ref
}  // namespace voxcast
