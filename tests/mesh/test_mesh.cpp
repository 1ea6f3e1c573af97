// The shared mesh pieces: the adjacency encoding and the priority bijection.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <unordered_set>

#include "base/clock.hpp"
#include "mesh/adjacency.hpp"
#include "mesh/priority.hpp"

using namespace gpugeom;

TEST(MeshAdjacency, EncodesSlotAndLocalIndex) {
  for (std::int32_t s : {0, 1, 7, 123456, (1 << 29) - 1})
    for (int k = 0; k < 4; ++k) {
      const std::int32_t e = mesh::enc(s, k);
      EXPECT_GE(e, 0);
      EXPECT_EQ(mesh::simplex_of(e), s);
      EXPECT_EQ(mesh::loc_of(e), k);
    }
}

TEST(MeshPriority, ScatterIsABijectionWithItsInverse) {
  std::mt19937 rng(5);
  for (int i = 0; i < 200000; ++i) {
    const std::uint32_t x = i < 1000 ? std::uint32_t(i) : rng();
    ASSERT_EQ(mesh::unscatter(mesh::scatter(x)), x);
    ASSERT_EQ(mesh::scatter(mesh::unscatter(x)), x);
  }
  EXPECT_EQ(mesh::scatter(0), 0u);
  EXPECT_EQ(mesh::unscatter(mesh::scatter(0xFFFFFFFFu)), 0xFFFFFFFFu);
  // neighbouring slots get unrelated keys: no run of increasing keys along increasing slots
  int rising = 0;
  for (std::uint32_t x = 1; x < 10001; ++x) rising += mesh::scatter(x) > mesh::scatter(x - 1);
  EXPECT_GT(rising, 4000);
  EXPECT_LT(rising, 6000);
}

TEST(MeshPriority, VoteKeysNameTheirVoterAndNewerRoundsWin) {
  std::unordered_set<std::uint64_t> seen;
  for (std::int32_t round : {0, 1, 1000, 0x7FFFFFFF})
    for (std::int32_t s = 0; s < 2000; ++s) {
      const std::uint64_t k = mesh::vote_key(round, s);
      ASSERT_EQ(mesh::voter_of(k), s);
      ASSERT_TRUE(seen.insert(k).second);
      if (round > 0) ASSERT_GT(k, mesh::vote_key(round - 1, (s * 7919) % 2000));
    }
}

TEST(Clock, MillisecondsBetweenTimePoints) {
  const Clock::time_point t0 = Clock::now();
  EXPECT_DOUBLE_EQ(ms_between(t0, t0 + std::chrono::microseconds(1500)), 1.5);
  EXPECT_GE(ms_since(t0), 0.0);
}
