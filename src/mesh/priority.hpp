// Priorities for settling conflicts without timing, shared by the mesh modules: flip votes
// (the largest key wins every simplex it touches) and ties between equally good points.
//
// A fixed bijection of 32-bit integers scatters neighbouring slots and indices (murmur3's
// finaliser): priorities by slot number would let only one flip per round go ahead along a
// chain of proposals with increasing slots, as in fans, and ties by index would insert the
// points of a run in index order, one round each. Its inverse names the winner from its key.
// scatter(0) == 0, so callers that need 0 to mean "none" offset their values by one.
#pragma once
#include <cstdint>

#include "base/hd.hpp"

namespace gpugeom::mesh {

GG_INLINE std::uint32_t scatter(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x85ebca6bu;
  x ^= x >> 13;
  x *= 0xc2b2ae35u;
  x ^= x >> 16;
  return x;
}
// Each step of scatter undone in reverse order (the odd multipliers' inverses mod 2^32).
GG_INLINE std::uint32_t unscatter(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7ed1b41du;
  x ^= (x >> 13) ^ (x >> 26);
  x *= 0xa5cb9243u;
  x ^= x >> 16;
  return x;
}

// A flip proposal's key: newer rounds win over stale keys left in the vote array (so it needs
// no clearing between rounds), then the scattered slot of the proposer.
GG_INLINE std::uint64_t vote_key(std::int32_t round, std::int32_t slot) {
  return (std::uint64_t(std::uint32_t(round)) << 32) | std::uint64_t(scatter(std::uint32_t(slot)));
}
GG_INLINE std::int32_t voter_of(std::uint64_t key) {
  return std::int32_t(unscatter(std::uint32_t(key)));
}

}  // namespace gpugeom::mesh
