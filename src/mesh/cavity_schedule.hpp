// The CPU executor's schedule for the Delaunay triangulations (issue 53): the points inserted
// one by one, each by its cavity (Bowyer-Watson), in a biased randomised order, the threads
// over chunks of the curve. What 2D and 3D share (delaunay2d/impl/one_by_one.inl and
// delaunay3d/impl/one_by_one.inl are the cavities themselves): the store's words read and
// written by several threads, the insertion order, and the chunks' schedule.
//
// The schedule: the sample (the top levels of the order) goes in first, on one thread. Then
// the threads insert the rest of the chunks of the curve, each chunk by the next thread to come
// free (one chunk a thread, or several where the module's rule allows). What a thread may change is
// the module's rule: in 2D only triangles whose finite vertices all lie in its chunk ("its own";
// the infinity vertex lies in every chunk), in 3D the tetrahedra it has locked. Where a point's
// walk or cavity reaches what the thread may not change, the point waits, and the waiting points
// go in by further rounds (modules that have them) and last on one thread. The modules' notes
// say why this is safe; which points wait depends on timing, the triangulation does not.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

#include <cuda/atomic>

#include "base/hd.hpp"

namespace gpugeom::mesh::cavities {

// Store words that other threads may be reading or writing (acquire / release: a neighbour
// pointer is published after the simplex it names).
GG_INLINE std::int32_t load_word(const std::int32_t* p) {
  cuda::atomic_ref<std::int32_t, cuda::thread_scope_system> r(*const_cast<std::int32_t*>(p));
  return r.load(cuda::memory_order_acquire);
}
GG_INLINE void store_word(std::int32_t* p, std::int32_t v) {
  cuda::atomic_ref<std::int32_t, cuda::thread_scope_system> r(*p);
  r.store(v, cuda::memory_order_release);
}

// The insertion order (a biased randomised insertion order, as CGAL's spatial sort makes, from
// Amenta, Choi and Rote): each point gets a level from a hash of its place on the curve, level
// l for a share 2^-(l+1) of the points; the levels go in from the highest down, each in curve
// order. In pure curve order one point may see a long chain of earlier ones (2D, two segments:
// the second one's points each took a fan over the whole first), and each insertion redid it.
constexpr int kLevels = 21;
// Levels from sample_level up: the sample, on one thread. A module whose threads may change
// only their own chunk's simplices (2D) needs a dense one (5: a 32nd of the points), as the
// points within reach of the sample's simplices across a border wait; one whose threads lock
// the simplices they change (3D) needs one only to spread the threads' first cavities (8: a
// 256th; at 16 threads the 32nd took a quarter of the insertion's time on one thread).
constexpr int kSampleLevel = 5;
constexpr int kLockingSampleLevel = 8;
// For the locking modules that share is a floor: what spreads the threads' first cavities does
// not grow with the points, and one thread inserting a 256th of them did (3D, 10^7 points, 16
// threads: 39 000 points alone, about 250 ms). Sparser levels are taken while the sample would
// hold more than this many points a thread (at 16 threads and 10^6 points level 8 holds 244).
constexpr std::int64_t kLockingSamplePerThread = 512;
inline int locking_sample_level(std::int64_t m, int threads) {
  int l = kLockingSampleLevel;
  while (l < kLevels - 1 && (m >> l) > kLockingSamplePerThread * threads) ++l;
  return l;
}
// Where the threads lock what they change, the sample itself goes in by the threads too, but
// for its top levels: those that hold no more than this many points a thread, on one thread
// first, so that the threads' first cavities lie apart. On one thread the sample held 15 threads
// idle (3D, 16 threads: 31-38 ms of a 10^6-point run, 50 ms at 10^7).
constexpr std::int64_t kAloneSamplePerThread = 16;
inline int alone_sample_level(std::int64_t m, int threads) {
  int l = 0;
  while (l < kLevels - 1 && (m >> l) > kAloneSamplePerThread * threads) ++l;
  return l;
}
// The parts a thread gets, in a module whose threads lock what they change (3D). The parts'
// costs differ (3D, 10^6 points on 16 threads, one part a thread: 360-560 ms on uniform points,
// 700-1 380 on a grid, whose parts along the hull's planes are mostly ties), and the stage lasts
// as long as its slowest thread: with several smaller parts a thread, taken as threads come free,
// the costs even out (uniform 10^6 on 16 threads: 640-670 ms against 690-710). The parts that run
// at one time lie apart on the curve (each_part_as_free), so no more points wait than with one
// part a thread. A module whose threads may change only their own part's simplices (2D) keeps one
// part a thread: its waiting points go in on one thread.
constexpr int kLockingPartsPerThread = 4;
// Rounds over other parts for the points that waited, at most (their marks q + r m stay
// below 2^31 for the 3D store's 1.4·10^8 points; 2D runs none).
constexpr int kMaxRounds = 8;
GG_INLINE int level_of(std::int32_t q) {
  std::uint64_t x = std::uint64_t(q) * 0x9E3779B97F4A7C15ull;
  x ^= x >> 31, x *= 0xBF58476D1CE4E5B9ull, x ^= x >> 29;
  int l = 0;
  while (l < kLevels - 1 && !(x & (std::uint64_t(1) << l))) ++l;
  return l;
}
// The points of [lo, hi) but those skipped (the first simplex's), by level from the highest
// down, each level in curve order, written from order[lo]; count[l]: how many have level l.
template <class Skip>
void order_by_level(std::int32_t lo, std::int32_t hi, Skip skip, std::int32_t* order,
                    std::int64_t* count) {
  std::fill(count, count + kLevels, 0);
  for (std::int32_t q = lo; q < hi; ++q)
    if (!skip(q)) ++count[level_of(q)];
  std::int64_t at[kLevels], sum = lo;
  for (int l = kLevels - 1; l >= 0; --l) at[l] = sum, sum += count[l];
  for (std::int32_t q = lo; q < hi; ++q)
    if (!skip(q)) order[at[level_of(q)]++] = q;
}

// The chunks' schedule over m points (curve positions), on ex's team (CPU). order: m entries of
// scratch. one: the inserter for one thread alone; each chunk's thread gets a copy of it with
// its part (fields chunk, own, rng, again; bool insert(q): false having changed nothing where
// the point must wait). The parts are the chunks of the curve (v / chunk) at first; a module
// with rounds gives others through its inserter (owner(v)). The
// module's hooks:
//   skip(q): the first simplex's vertices (not inserted);
//   chunks(nc, chunk): the chunks are [c * chunk, (c + 1) * chunk) for c < nc (1 where the
//     threads do not pay: one thread inserts all), before any insertion;
//   put(I, c, q): one thread alone inserts q for chunk c (it must go in);
//   threads_begin(points, split) / threads_done(k): before and after the threads (one thread;
//     points[c]: how many part c's thread may insert; split: an inserter that knows the parts;
//     k points went in, the others given wait);
//   split(r, parts, I, waiting): round r's parts, set in I (I.owner(v) < parts); false: no
//     more rounds (2D: its slots follow each point's chunk of the curve);
//   enter(I, c) / leave(I, c): chunk c's thread begins with / ends with its inserter I;
//   mark(what): a profile mark.
// Returns how many points waited.
// alone_level (a module whose threads lock what they change): the sample's levels from it up
// go in on one thread, those below it by the threads, chunk by chunk, before the rest.
template <class E, class Ins, class Hooks>
std::int64_t insert_by_chunks(E& ex, std::int32_t m, std::int32_t* order, Ins& one, Hooks& h,
                              int sample_level = kSampleLevel, int parts_per_thread = 1,
                              int alone_level = 0) {
  const int nt = ex.team_size();
  const std::int64_t nc = nt <= 1 || m < 64 * std::int64_t(1 << kSampleLevel) * nt
                              ? 1
                              : std::int64_t(nt) * std::max(1, parts_per_thread);
  const std::int64_t teams = nc == 1 ? 1 : nt;  // threads that insert side by side
  const std::int64_t chunk = (std::int64_t(m) + nc - 1) / nc;
  h.chunks(nc, chunk);
  auto skip = [&](std::int32_t q) { return h.skip(q); };
  std::vector<std::int64_t> counts(std::size_t(nc) * kLevels);
  auto bounds = [&](std::int64_t c, std::int32_t& lo, std::int32_t& hi) {
    lo = std::int32_t(std::min<std::int64_t>(m, c * chunk));
    hi = std::int32_t(std::min<std::int64_t>(m, lo + chunk));
  };
  auto each_part = [&](std::int64_t parts, auto f) {  // each by some thread (any team size)
    ex.team([&](const auto& team) {
      for (std::int64_t c = team.rank; c < parts; c += team.size) f(c);
    });
  };
  auto each_chunk = [&](auto f) { each_part(nc, f); };
  // Each part by the next thread to come free. The parts are dealt out as nt shares of
  // consecutive ones, taken in the order: every share's first part, then every share's second,
  // and so on, so that the parts running at one time lie apart on the curve (parts next to each
  // other in space wait for each other's tetrahedra).
  auto each_part_as_free = [&](std::int64_t parts, auto f) {
    const std::int64_t shares = std::min<std::int64_t>(parts, nt);
    const std::int64_t per = (parts + shares - 1) / shares;
    std::atomic<std::int64_t> taken{0};
    ex.team([&](const auto&) {
      for (std::int64_t i; (i = taken.fetch_add(1, std::memory_order_relaxed)) < shares * per;) {
        const std::int64_t c = (i % shares) * per + i / shares;
        if (c < parts) f(c);
      }
    });
  };
  each_chunk([&](std::int64_t c) {
    std::int32_t lo, hi;
    bounds(c, lo, hi);
    order_by_level(lo, hi, skip, order, counts.data() + c * kLevels);
  });
  // Where level l of chunk c begins in order.
  std::vector<std::int64_t> begin(std::size_t(nc) * kLevels);
  for (std::int64_t c = 0; c < nc; ++c) {
    std::int32_t lo, hi;
    bounds(c, lo, hi);
    std::int64_t at = lo;
    for (int l = kLevels - 1; l >= 0; --l)
      begin[c * kLevels + l] = at, at += counts[c * kLevels + l];
  }
  auto level = [&](std::int64_t c, int l, auto f) {
    const std::int64_t from = begin[c * kLevels + l], to = from + counts[c * kLevels + l];
    for (std::int64_t i = from; i < to; ++i) f(order[i]);
  };
  // The sample level by level over all chunks (one chunk alone: every level); where the threads
  // take its lower levels, only those from alone_level up.
  const int lowest = nc == 1 ? 0 : std::max(sample_level, alone_level);
  for (int l = kLevels - 1; l >= lowest; --l)
    for (std::int64_t c = 0; c < nc; ++c) level(c, l, [&](std::int32_t q) { h.put(one, c, q); });
  h.mark("sample");
  if (nc == 1) return 0;
  // The threads, each over its part's points (pts(c, f): f for each, in order), its inserter a
  // copy of `split` (which knows the parts: Ins::owner); those that must wait go to wait[c].
  auto threads = [&](std::int64_t parts, const Ins& split, std::int32_t again, auto pts,
                     std::vector<std::vector<std::int32_t>>& wait) {
    wait.assign(std::size_t(parts), {});
    each_part_as_free(parts, [&](std::int64_t c) {
      Ins mine = split;
      mine.own = std::int32_t(c), mine.again = again;
      mine.rng += std::uint32_t(c + again);
      h.enter(mine, c);
      std::vector<std::int32_t>& w = wait[std::size_t(c)];
      pts(c, [&](std::int32_t q) {
        if (!mine.insert(q)) w.push_back(q);
      });
      h.leave(mine, c);
    });
    std::int64_t n = 0;
    for (const auto& x : wait) n += std::int64_t(x.size());
    return n;
  };
  // The threads over levels [lo, hi) of their chunks; returns how many waited.
  std::vector<std::vector<std::int32_t>> waiting;
  auto levels_by_threads = [&](int lo, int hi) {
    Ins split = one;  // (the parts: the chunks of the curve)
    split.chunk = chunk;
    std::vector<std::int64_t> sizes(static_cast<std::size_t>(nc));
    std::int64_t given = 0;
    for (std::int64_t c = 0; c < nc; ++c)
      for (int l = hi - 1; l >= lo; --l) sizes[std::size_t(c)] += counts[c * kLevels + l];
    for (const std::int64_t k : sizes) given += k;
    h.threads_begin(sizes, split);
    const std::int64_t w = threads(
        nc, split, 0,
        [&](std::int64_t c, auto f) {
          for (int l = hi - 1; l >= lo; --l) level(c, l, f);
        },
        waiting);
    h.threads_done(given - w);
    return w;
  };
  // The sample's lower levels by the threads; those that wait (a third of them at 16 threads: at
  // these sparse levels the cavities are large), on one thread, before the rest (whose cavities
  // are small only once the whole sample is in).
  std::int64_t sample_waited = 0;
  if (alone_level > sample_level) {
    sample_waited = levels_by_threads(sample_level, alone_level);
    for (std::int64_t c = 0; c < std::int64_t(waiting.size()); ++c)
      for (const std::int32_t q : waiting[std::size_t(c)]) h.put(one, c, q);
    h.mark("sample_threads");
  }
  std::int64_t waited = levels_by_threads(0, sample_level);
  h.mark("chunks");
  Ins split = one;
  std::vector<std::int64_t> sizes;
  // The waiting points lie along the chunks' borders, and a chunk of the curve touches several
  // others in space, not only its neighbours on the curve: chunks shifted along the curve keep
  // most of those borders (3D, 4 threads: a shift left 60 % waiting). Modules that can
  // (h.split(r, split, waiting) gives round r's parts, false where it has none) insert them in
  // further rounds of threads over other parts (3D: slabs across an axis), while a round
  // inserts at least an eighth of what it is given.
  std::int32_t again = m;  // (round r's attempts mark with q + r m: a first one left marks q)
  for (int r = 1; r <= kMaxRounds && waited > 256 * teams; ++r) {
    // (half as many parts a round, down to two: the waiting points are missing from the
    // tetrahedralisation together, so their cavities are large and cross thin parts' borders)
    const std::int64_t parts = std::max<std::int64_t>(2, teams >> r);
    split = one;
    if (!h.split(r, parts, split, waiting)) break;
    std::vector<std::vector<std::int32_t>> by_owner(static_cast<std::size_t>(parts));
    for (const auto& w : waiting)
      for (const std::int32_t q : w) by_owner[std::size_t(split.owner(q))].push_back(q);
    sizes.assign(std::size_t(parts), 0);
    for (std::int64_t c = 0; c < parts; ++c) {
      std::sort(by_owner[std::size_t(c)].begin(), by_owner[std::size_t(c)].end());
      sizes[std::size_t(c)] = std::int64_t(by_owner[std::size_t(c)].size());
    }
    h.threads_begin(sizes, split);
    const std::int64_t given = waited;
    waited = threads(
        parts, split, again,
        [&](std::int64_t c, auto f) {
          for (const std::int32_t q : by_owner[std::size_t(c)]) f(q);
        },
        waiting);
    h.threads_done(given - waited);
    h.mark("rounds");
    again += m;
    if (8 * (given - waited) < given) break;
  }
  // The points still waiting, in curve order, on one thread, each walk from the last
  // insertion's simplex.
  one.again = again;
  for (std::int64_t c = 0; c < std::int64_t(waiting.size()); ++c) {
    std::vector<std::int32_t>& wait = waiting[std::size_t(c)];
    std::sort(wait.begin(), wait.end());
    for (const std::int32_t q : wait) h.put(one, c, q);
  }
  h.mark("deferred");
  return sample_waited + waited;
}

}  // namespace gpugeom::mesh::cavities
