// Hilbert curve keys for 2D/3D points (Skilling's transpose formulation, from his published
// description). Points are quantised onto a 2^B grid over their bounding box; nearby keys mean
// nearby points, which keeps insertion batches and memory accesses local.
#pragma once
#include <cstdint>

#include "base/hd.hpp"

namespace gpugeom::spatial {

template <int D>
struct HilbertBits {
  static constexpr int value = D == 2 ? 31 : 21;  // 62 / 63 key bits
};

struct Box {
  double lo[3], hi[3];
};

// Hilbert index of integer coordinates x[0..D-1] < 2^B.
template <int D, int B>
GG_INLINE std::uint64_t hilbert_index(std::uint32_t x[D]) {
  const std::uint32_t m = 1u << (B - 1);
  for (std::uint32_t q = m; q > 1; q >>= 1) {  // inverse undo excess work
    const std::uint32_t p = q - 1;
    for (int i = 0; i < D; ++i) {
      if (x[i] & q) {
        x[0] ^= p;
      } else {
        std::uint32_t t = (x[0] ^ x[i]) & p;
        x[0] ^= t;
        x[i] ^= t;
      }
    }
  }
  for (int i = 1; i < D; ++i) x[i] ^= x[i - 1];  // Gray encode
  std::uint32_t t = 0;
  for (std::uint32_t q = m; q > 1; q >>= 1)
    if (x[D - 1] & q) t ^= q - 1;
  for (int i = 0; i < D; ++i) x[i] ^= t;
  std::uint64_t key = 0;  // interleave the transposed bits, most significant first
  for (int b = B - 1; b >= 0; --b)
    for (int i = 0; i < D; ++i) key = (key << 1) | ((x[i] >> b) & 1u);
  return key;
}

template <int D>
GG_INLINE std::uint64_t hilbert_key(const double* p, const Box& box) {
  constexpr int B = HilbertBits<D>::value;
  const double cells = double((1u << B) - 1);
  std::uint32_t x[D];
  for (int i = 0; i < D; ++i) {
    double ext = box.hi[i] - box.lo[i];
    double t = ext > 0 ? (p[i] - box.lo[i]) / ext : 0.0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    x[i] = std::uint32_t(t * cells);
  }
  return hilbert_index<D, B>(x);
}

}  // namespace gpugeom::spatial
