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

// The bits of x (below 2^21 for D = 3, 2^32 for D = 2) spread D apart: bit b to bit D b.
template <int D>
GG_INLINE std::uint64_t spread_bits(std::uint32_t x) {
  std::uint64_t v = x;
  if constexpr (D == 2) {
    v = (v | v << 16) & 0x0000FFFF0000FFFFull;
    v = (v | v << 8) & 0x00FF00FF00FF00FFull;
    v = (v | v << 4) & 0x0F0F0F0F0F0F0F0Full;
    v = (v | v << 2) & 0x3333333333333333ull;
    v = (v | v << 1) & 0x5555555555555555ull;
  } else {
    static_assert(D == 3, "2D or 3D");
    v &= 0x1FFFFF;
    v = (v | v << 32) & 0x001F00000000FFFFull;
    v = (v | v << 16) & 0x001F0000FF0000FFull;
    v = (v | v << 8) & 0x100F00F00F00F00Full;
    v = (v | v << 4) & 0x10C30C30C30C30C3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
  }
  return v;
}

// Hilbert index of integer coordinates x[0..D-1] < 2^B. Without branches (which bit is set is
// a coin toss per level: on the CPU executor the branching form took most of the points'
// preparation) and with the transposed bits interleaved by spreading; tests/spatial compares
// it with the bit-by-bit form on random coordinates.
template <int D, int B>
GG_INLINE std::uint64_t hilbert_index(std::uint32_t x[D]) {
  const std::uint32_t m = 1u << (B - 1);
  for (std::uint32_t q = m; q > 1; q >>= 1) {  // inverse undo excess work
    const std::uint32_t p = q - 1;
    for (int i = 0; i < D; ++i) {
      // (x[i] & q) ? x[0] ^= p : exchange the low bits (below q) of x[0] and x[i]
      const std::uint32_t set = 0u - std::uint32_t((x[i] & q) != 0);
      const std::uint32_t t = (x[0] ^ x[i]) & p & ~set;
      x[0] ^= (p & set) | t;
      if (i > 0) x[i] ^= t;
    }
  }
  for (int i = 1; i < D; ++i) x[i] ^= x[i - 1];  // Gray encode
  std::uint32_t t = 0;
  for (std::uint32_t q = m; q > 1; q >>= 1)
    t ^= (0u - std::uint32_t((x[D - 1] & q) != 0)) & (q - 1);
  std::uint64_t key = 0;  // the transposed bits interleaved, most significant first: x[0]'s
  for (int i = 0; i < D; ++i)
    key |= spread_bits<D>(x[i] ^ t) << (D - 1 - i);  // bit b at D b + D - 1
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
