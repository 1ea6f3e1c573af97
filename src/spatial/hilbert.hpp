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

// The same index by tables, a few levels a lookup (the host's: the branch-free form above
// spends some 30 operations a level on both coordinates, about 100 ns a 2D key on the 2-core
// machine, a tenth of 2D Delaunay's time there; device code keeps the form above, whose keys
// these equal: tests/spatial compares them). Skilling's transform read top down is a
// transducer: at each level the bits seen are the raw bits under a signed permutation of the
// axes (what the levels above did to the lower bits), the level's steps compose one more onto
// it (a set bit of axis i flips axis 0's lower bits, a clear one swaps axis 0's with axis i's),
// and the Gray code's parity of the last axis above the level flips the level's output bits.
// The state is that permutation, its flips and the parity; a table maps a state and K levels'
// raw bits to their key bits and the next state.
namespace hilbert_detail {
template <int D>
struct State {
  int perm[3] = {0, 1, 2};  // the bit seen on axis i is raw axis perm[i]'s, flipped by flip[i]
  int flip[3] = {0, 0, 0};
  int parity = 0;  // the Gray-coded last axis's bits above this level, summed mod 2
  static constexpr int kCount = D * D * (1 << D) * 2;
  constexpr int code() const {
    return ((perm[0] + D * perm[1]) * (1 << D) + bits(flip)) * 2 + parity;
  }
  static constexpr int bits(const int* b) {
    int v = 0;
    for (int i = 0; i < D; ++i) v |= b[i] << i;
    return v;
  }
  static constexpr State decode(int c) {
    State s;
    s.parity = c & 1, c >>= 1;
    for (int i = 0; i < D; ++i) s.flip[i] = (c >> i) & 1;
    c >>= D;
    s.perm[0] = c % D, s.perm[1] = c / D;
    if (D == 3) s.perm[2] = 3 - s.perm[0] - s.perm[1];
    return s;
  }
  constexpr bool valid() const {
    int seen = 0;
    for (int i = 0; i < D; ++i) seen |= perm[i] >= 0 && perm[i] < D ? 1 << perm[i] : 1 << 7;
    return seen == (1 << D) - 1;
  }
  // One level: raw bits a; returns its D key bits (axis 0's highest), and moves to the next.
  constexpr int step(const int* a) {
    int c[3] = {0, 0, 0}, d[3] = {0, 0, 0};
    for (int i = 0; i < D; ++i) c[i] = a[perm[i]] ^ flip[i];
    for (int i = 0; i < D; ++i) {
      if (c[i]) {
        flip[0] ^= 1;
      } else if (i > 0) {
        const int p = perm[0], f = flip[0];
        perm[0] = perm[i], flip[0] = flip[i], perm[i] = p, flip[i] = f;
      }
    }
    d[0] = c[0];
    for (int i = 1; i < D; ++i) d[i] = c[i] ^ d[i - 1];
    int out = 0;
    for (int i = 0; i < D; ++i) out |= (d[i] ^ parity) << (D - 1 - i);
    parity ^= d[D - 1];
    return out;
  }
};
// Entry: the K levels' key bits above the next state's code. Input: axis i's K bits at bits
// K i to K i + K - 1, the top level highest.
template <int D, int K>
struct Table {
  static constexpr int kInputs = 1 << (D * K);
  std::uint16_t e[State<D>::kCount][kInputs] = {};
  constexpr Table() {
    for (int c = 0; c < State<D>::kCount; ++c)
      for (int in = 0; in < kInputs; ++in) {
        State<D> s = State<D>::decode(c);
        e[c][in] = 0;
        if (!s.valid()) continue;  // (codes no permutation has)
        int out = 0;
        for (int j = K - 1; j >= 0; --j) {
          int a[3] = {0, 0, 0};
          for (int i = 0; i < D; ++i) a[i] = (in >> (K * i + j)) & 1;
          out |= s.step(a) << (D * j);
        }
        e[c][in] = std::uint16_t(out << 8 | s.code());
      }
  }
};
// (Made by the compiler: read-only data, not state built at the first call.)
template <int D, int K>
inline constexpr Table<D, K> kTable{};
// Levels [lo, lo + K) of x through the table from state c: the key bits there, c moved on.
template <int D, int K>
inline std::uint64_t levels(const Table<D, K>& t, const std::uint32_t* x, int lo, int& c) {
  std::uint32_t in = 0;
  for (int i = 0; i < D; ++i) in |= ((x[i] >> lo) & ((1u << K) - 1)) << (K * i);
  const std::uint16_t e = t.e[c][in];
  c = e & 0xFF;
  return std::uint64_t(e >> 8) << (D * lo);
}
}  // namespace hilbert_detail

template <int D, int B>
inline std::uint64_t hilbert_index_by_tables(const std::uint32_t* x) {
  constexpr int K = D == 2 ? 4 : 2;
  const auto& one = hilbert_detail::kTable<D, 1>;
  const auto& many = hilbert_detail::kTable<D, K>;
  static_assert(hilbert_detail::State<D>::kCount <= 256, "codes in a byte");
  int c = hilbert_detail::State<D>().code();
  std::uint64_t key = 0;
  int lo = B;
  for (; lo % K != 0;) key |= hilbert_detail::levels<D, 1>(one, x, --lo, c);
  while (lo > 0) lo -= K, key |= hilbert_detail::levels<D, K>(many, x, lo, c);
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
#if defined(__CUDA_ARCH__)
  return hilbert_index<D, B>(x);
#else
  return hilbert_index_by_tables<D, B>(x);
#endif
}

}  // namespace gpugeom::spatial
