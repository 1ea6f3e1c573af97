// The work lists of a mesh module's rounds (flip rounds, insertion rounds), on the executor.
//
// Round r works through list r & 1 and appends the next round's entries to list (r + 1) & 1.
// The two lengths live in the module's counter record on the executor (so that the host reads
// them with its other counters in one copy, once per few rounds), and every kernel of a round
// reads its length there (the executor's counted launches): no round waits for the host, and a
// round past the last one finds an empty list and does nothing.
#pragma once
#include <cstdint>

#include "base/hd.hpp"

namespace gpugeom::mesh {

struct WorkLists {
  std::int32_t* list[2];
  std::int64_t* len;  // len[0], len[1], inside the module's counters
  // (selects, not list[r & 1]: an indexed array would keep a team's copy in local memory)
  GG_HD std::int32_t* current(std::int32_t r) const { return (r & 1) ? list[1] : list[0]; }
  GG_HD std::int32_t* next(std::int32_t r) const { return (r & 1) ? list[0] : list[1]; }
  GG_HD std::int64_t* count(std::int32_t r) const { return (r & 1) ? len + 1 : len; }
  GG_HD std::int64_t* next_count(std::int32_t r) const { return (r & 1) ? len : len + 1; }
};

// Compaction inside a team (the tail rounds that run in one launch), in index order: thread r
// takes the r-th contiguous range of [0, n), counts the kept items, and a scan over the
// threads gives each its first output slot; emit(i, slot) for every kept i, in order, as the
// executor's compaction would. Returns the count (every thread calls it).
template <class Team, class Keep, class Emit>
GG_HD std::int64_t team_compact(const Team& t, std::int64_t n, Keep keep, Emit emit) {
  const std::int64_t per = (n + t.size - 1) / t.size;
  const std::int64_t lo = n < t.rank * per ? n : t.rank * per;
  const std::int64_t hi = n < lo + per ? n : lo + per;
  std::int64_t c = 0, total = 0;
  for (std::int64_t i = lo; i < hi; ++i) c += keep(i);
  std::int64_t at = t.exclusive_scan(c, &total);
  for (std::int64_t i = lo; i < hi; ++i)
    if (keep(i)) emit(i, at++);
  return total;
}

}  // namespace gpugeom::mesh
