#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "gpugeom/generate.hpp"
#include "gpugeom/spatial.hpp"
#include "spatial/hilbert.hpp"

using namespace gpugeom;

// The defining property of the Hilbert curve: consecutive indices are adjacent cells, and
// every cell gets exactly one index.
template <int D, int B>
void check_curve() {
  const std::uint32_t side = 1u << B;
  std::uint64_t cells = 1;
  for (int d = 0; d < D; ++d) cells *= side;
  std::vector<std::array<std::uint32_t, 3>> at(cells, {~0u, ~0u, ~0u});
  for (std::uint64_t c = 0; c < cells; ++c) {
    std::uint32_t x[D], orig[3] = {0, 0, 0};
    for (int d = 0; d < D; ++d) x[d] = orig[d] = std::uint32_t(c >> (B * d)) & (side - 1);
    std::uint64_t h = spatial::hilbert_index<D, B>(x);
    ASSERT_LT(h, cells);
    ASSERT_EQ(at[h][0], ~0u) << "index " << h << " used twice";
    at[h] = {orig[0], orig[1], orig[2]};
  }
  for (std::uint64_t h = 1; h < cells; ++h) {
    int dist = 0;
    for (int d = 0; d < D; ++d) dist += std::abs(int(at[h][d]) - int(at[h - 1][d]));
    ASSERT_EQ(dist, 1) << "indices " << h - 1 << " and " << h << " are not adjacent";
  }
}

// The index as first written (Skilling's transpose form, a branch a level and the bits
// interleaved one at a time): the library's branch-free form must give the same keys, as
// they fix the curve order, and with it every output order.
template <int D, int B>
std::uint64_t hilbert_bit_by_bit(std::uint32_t x[D]) {
  const std::uint32_t m = 1u << (B - 1);
  for (std::uint32_t q = m; q > 1; q >>= 1) {
    const std::uint32_t p = q - 1;
    for (int i = 0; i < D; ++i) {
      if (x[i] & q) {
        x[0] ^= p;
      } else {
        const std::uint32_t t = (x[0] ^ x[i]) & p;
        x[0] ^= t;
        x[i] ^= t;
      }
    }
  }
  for (int i = 1; i < D; ++i) x[i] ^= x[i - 1];
  std::uint32_t t = 0;
  for (std::uint32_t q = m; q > 1; q >>= 1)
    if (x[D - 1] & q) t ^= q - 1;
  for (int i = 0; i < D; ++i) x[i] ^= t;
  std::uint64_t key = 0;
  for (int b = B - 1; b >= 0; --b)
    for (int i = 0; i < D; ++i) key = (key << 1) | ((x[i] >> b) & 1u);
  return key;
}
template <int D, int B>
void check_against_bit_by_bit(int n) {
  std::mt19937_64 r(7);
  for (int k = 0; k < n; ++k) {
    std::uint32_t a[D], b[D];
    for (int d = 0; d < D; ++d) a[d] = b[d] = std::uint32_t(r() & ((std::uint64_t(1) << B) - 1));
    const std::uint64_t want = hilbert_bit_by_bit<D, B>(b);
    for (int d = 0; d < D; ++d) b[d] = a[d];
    const std::uint64_t tables = spatial::hilbert_index_by_tables<D, B>(b);
    const std::uint64_t got = spatial::hilbert_index<D, B>(a);
    ASSERT_EQ(got, want) << "case " << k;
    ASSERT_EQ(tables, want) << "case " << k << " (by tables)";
  }
}
TEST(Hilbert, SameKeysAsBitByBit) {
  check_against_bit_by_bit<3, 21>(200000);
  check_against_bit_by_bit<2, 31>(200000);
  check_against_bit_by_bit<3, 4>(5000);
  check_against_bit_by_bit<2, 5>(5000);
}

TEST(Hilbert, Curve2d) {
  check_curve<2, 5>();
}
TEST(Hilbert, Curve3d) {
  check_curve<3, 4>();
}

TEST(Hilbert, OrderIsAPermutationAndLocal) {
  auto pts = generate3d("uniform", 200000, 3);
  auto order = hilbert_order(pts, Backend::Cpu);
  ASSERT_EQ(order.size(), pts.size());
  std::vector<char> seen(pts.size(), 0);
  for (auto i : order) {
    ASSERT_GE(i, 0);
    ASSERT_LT(std::size_t(i), pts.size());
    ASSERT_FALSE(seen[i]);
    seen[i] = 1;
  }
  // Locality: consecutive points along the curve are far closer than random pairs.
  double along = 0, random = 0;
  for (std::size_t k = 1; k < order.size(); ++k) {
    auto& a = pts[order[k - 1]];
    auto& b = pts[order[k]];
    auto& c = pts[k - 1];
    auto& d = pts[k];
    along += std::hypot(a.x - b.x, a.y - b.y, a.z - b.z);
    random += std::hypot(c.x - d.x, c.y - d.y, c.z - d.z);
  }
  EXPECT_LT(along * 20, random);
}

TEST(Hilbert, RejectsNonFinite) {
  std::vector<Point2> p{{0, 0}, {NAN, 1}};
  EXPECT_THROW(hilbert_order(p, Backend::Cpu), Error);
  std::vector<Point2> empty;
  EXPECT_TRUE(hilbert_order(empty, Backend::Cpu).empty());
}
