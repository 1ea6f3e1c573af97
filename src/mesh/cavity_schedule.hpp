// The CPU executor's schedule for the Delaunay triangulations and the 3D hull (issue 53): the
// points inserted one by one, each by its cavity (Bowyer-Watson; the facets a point sees, for
// the hull), in a biased randomised order, the threads over chunks of the curve. What 2D, 3D and
// the hull share (delaunay2d/impl/one_by_one.inl, delaunay3d/impl/one_by_one.inl and
// hull3d/impl/one_by_one.inl are the cavities themselves): the store's words read and written by
// several threads, the insertion order, and the chunks' schedule.
//
// The schedule: the sample (the top levels of the order) goes in first, on one thread. Then
// the threads insert the rest of the chunks of the curve, each chunk by the next thread to come
// free (one chunk a thread, or several where the module's rule allows). What a thread may change is
// the module's rule: in 2D only triangles whose finite vertices all lie in its chunk ("its own";
// the infinity vertex lies in every chunk), and in the hull likewise its own facets, in 3D the
// tetrahedra it has locked. Where a point's
// walk or cavity reaches what the thread may not change, the point waits, and the waiting points
// go in by further rounds (modules that have them) and last on one thread. The modules' notes
// say why this is safe; which points wait depends on timing, the triangulation does not.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
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
// only their own chunk's simplices (2D, the hull) needs a dense one (5: a 32nd of the points), as
// the points within reach of the sample's simplices across a border wait; one whose threads lock
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
inline int alone_sample_level(std::int64_t m, int threads, int level_bits = 1) {
  int l = 0;
  while (l < kLevels - 1 && (m >> (level_bits * l)) > kAloneSamplePerThread * threads) ++l;
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
// Rounds over other parts for the points that waited, at most (2D and the hull run none).
constexpr int kMaxRounds = 8;
// bits: each level holds a 2^bits-th as many points as the one below (1: a half, as above).
GG_INLINE int level_of(std::int32_t q, int bits = 1) {
  std::uint64_t x = std::uint64_t(q) * 0x9E3779B97F4A7C15ull;
  x ^= x >> 31, x *= 0xBF58476D1CE4E5B9ull, x ^= x >> 29;
  const std::uint64_t mask = (std::uint64_t(1) << bits) - 1;
  int l = 0;
  while (l < kLevels - 1 && !((x >> (bits * l)) & mask)) ++l;
  return l;
}
// The points of [lo, hi) but those skipped (the first simplex's), by level from the highest
// down, each level in curve order, written from order[lo]; count[l]: how many have level l.
template <class Skip>
void order_by_level(std::int32_t lo, std::int32_t hi, Skip skip, std::int32_t* order,
                    std::int64_t* count, int bits = 1) {
  std::fill(count, count + kLevels, 0);
  for (std::int32_t q = lo; q < hi; ++q)
    if (!skip(q)) ++count[level_of(q, bits)];
  std::int64_t at[kLevels], sum = lo;
  for (int l = kLevels - 1; l >= 0; --l) at[l] = sum, sum += count[l];
  for (std::int32_t q = lo; q < hi; ++q)
    if (!skip(q)) order[at[level_of(q, bits)]++] = q;
}

// How the schedule runs (insert_by_chunks). The defaults are for a module whose threads may
// change only their own chunk's simplices (2D, the hull); locking_schedule gives a locking module's
// (3D).
struct Schedule {
  int sample_level = kSampleLevel;  // the sample: the levels from this one up
  int parts_per_thread = 1;         // the chunks of the curve, per thread
  int alone_level = 0;  // the sample's levels from this one up on one thread, the rest by threads
  int level_bits = 1;   // level_of's: each level a 2^level_bits-th of the one below
  // The threads lock what they change (3D): a thread with no part left splits off the back half
  // of the part with most points left (PartPoints), and a part's waiting points are tried again
  // when its own are done.
  bool locks = false;
};
// Parts with fewer points left than this are not split (a split part's thread walks to its
// points from afar once, and its slots' range has a floor).
constexpr std::int64_t kMinSplit = 128;
// Parts split off in a stage, at most, per thread.
constexpr std::int64_t kSplitsPerThread = 4;
inline Schedule locking_schedule(std::int64_t m, int threads) {
  Schedule s;
  s.sample_level = locking_sample_level(m, threads);
  s.parts_per_thread = kLockingPartsPerThread;
  s.alone_level = alone_sample_level(m, threads);
  s.locks = true;
  return s;
}

// The points of the parts the threads take, and what is left of each. A part's points are taken
// one at a time from its front; where the module allows it (its threads lock what they change),
// a thread with no part left to take splits off the back half of the part with the most points
// left and inserts those. The parts' costs differ (3D grid, 10^6 points on 16 threads: 160-420 ms,
// the heaviest along the hull's planes, whose points are mostly ties), and without splitting the
// stage ran 28 % past the parts' mean load per thread (the last parts taken were heavy ones).
// The back half lies apart on the curve from where the part's own thread works, so the two
// meet only at one border.
struct PartPoints {
  struct Span {
    const std::int32_t* at = nullptr;
    std::int64_t n = 0;
    std::int64_t root = -1;  // the given part its points come from (-1: none yet)
  };
  std::vector<Span> span;  // per part, then the parts split off (up to `cap` in all)
  std::unique_ptr<std::atomic<std::uint64_t>[]> left;  // per part: next << 32 | end
  std::atomic<std::int64_t> made;                      // parts so far (given and split off)
  std::int64_t cap;
  PartPoints(std::vector<Span> given, std::int64_t cap_)
      : span(std::move(given)),
        left(new std::atomic<std::uint64_t>[std::size_t(cap_)]),
        made(std::int64_t(span.size())),
        cap(cap_) {
    for (std::int64_t c = 0; c < cap; ++c)
      left[c].store(c < made ? std::uint64_t(span[std::size_t(c)].n) : 0,
                    std::memory_order_relaxed);
    for (std::size_t c = 0; c < span.size(); ++c) span[c].root = std::int64_t(c);
    span.resize(std::size_t(cap));
  }
  // The next point of part c (an index into its span), or -1 where none is left.
  std::int64_t take(std::int64_t c) {
    std::uint64_t x = left[c].load(std::memory_order_relaxed);
    for (;;) {
      const std::uint64_t next = x >> 32, end = x & 0xffffffffu;
      if (next >= end) return -1;
      if (left[c].compare_exchange_weak(x, x + (std::uint64_t(1) << 32), std::memory_order_acq_rel,
                                        std::memory_order_relaxed))
        return std::int64_t(next);
    }
  }
  // Splits off the back half of the part with the most points left, if at least min_left:
  // the new part's number (perhaps with no points, where the others took them first), or -1.
  // room(id, root, n): the module readies the new part's inserter for up to n points of given
  // part root's (false: it has no room, and nothing is split).
  template <class Room>
  std::int64_t split_off(std::int64_t min_left, Room room) {
    std::int64_t best = -1, most = min_left;
    const std::int64_t k = std::min(made.load(std::memory_order_acquire), cap);
    for (std::int64_t c = 0; c < k; ++c) {
      const std::uint64_t x = left[c].load(std::memory_order_acquire);  // (then its span)
      const std::int64_t n = std::int64_t(x & 0xffffffffu) - std::int64_t(x >> 32);
      if (n > most) best = c, most = n;
    }
    if (best < 0) return -1;
    const std::int64_t id = made.fetch_add(1, std::memory_order_acq_rel);
    const std::int64_t root = span[std::size_t(best)].root;
    if (id >= cap || !room(id, root, most / 2 + 1)) return -1;
    std::uint64_t x = left[best].load(std::memory_order_relaxed);
    std::uint64_t mid = 0, end = 0;
    for (;;) {  // (the part's points left only shrink, so no more than most / 2 + 1 are taken)
      const std::uint64_t next = x >> 32;
      end = x & 0xffffffffu;
      if (end < next + std::uint64_t(min_left)) {
        mid = end;
        break;
      }
      mid = next + (end - next) / 2;
      if (left[best].compare_exchange_weak(x, (next << 32) | mid, std::memory_order_acq_rel,
                                           std::memory_order_relaxed))
        break;
    }
    const Span& b = span[std::size_t(best)];
    span[std::size_t(id)] = Span{b.at + mid, std::int64_t(end - mid), root};
    left[id].store(end - mid, std::memory_order_release);
    return id;
  }
};

// The hooks a module whose threads may change only their own chunk's simplices (2D, the hull)
// has no use for: nothing to ready around the threads, no rounds over other parts (each point's
// slots follow its chunk of the curve), and no split parts (insert_by_chunks splits none where
// the schedule does not lock: enter_split is never asked).
template <class Ins>
struct OwnChunkHooks {
  void threads_begin(const std::vector<std::int64_t>&, const Ins&, std::int64_t) {}
  bool split(int, std::int64_t, Ins&, const std::vector<std::vector<std::int32_t>>&) {
    return false;
  }
  void threads_done(std::int64_t) {}
  bool enter_split(Ins&, std::int64_t, std::int64_t, std::int64_t) { return false; }
};

// The chunks' schedule over m points (curve positions), on ex's team (CPU). order: m entries of
// scratch. one: the inserter for one thread alone; each chunk's thread gets a copy of it with
// its part (fields chunk, own, rng; bool insert(q): false having changed nothing where
// the point must wait). The parts are the chunks of the curve (v / chunk) at first; a module
// with rounds gives others through its inserter (owner(v)). The
// module's hooks:
//   skip(q): the first simplex's vertices (not inserted);
//   chunks(nc, chunk): the chunks are [c * chunk, (c + 1) * chunk) for c < nc (1 where the
//     threads do not pay: one thread inserts all), before any insertion;
//   put(I, c, q): one thread alone inserts q for chunk c (it must go in);
//   threads_begin(points, split, most) / threads_done(k): before and after the threads (one
//     thread; points[c]: how many part c's thread may insert; split: an inserter that knows the
//     parts; most: the parts given and split off are numbered below it; k points went in, the
//     others given wait);
//   split(r, parts, I, waiting): round r's parts, set in I (I.owner(v) < parts); false: no
//     more rounds (2D: its slots follow each point's chunk of the curve);
//   enter(I, c) / leave(I, c): chunk c's thread begins with / ends with its inserter I;
//   enter_split(I, id, root, n): (where parts are split) part id, split off given part root's
//     points, begins with I, for up to n points; false: no room for it (leave(I, id) follows);
//   mark(what): a profile mark.
// Returns how many points waited.
template <class E, class Ins, class Hooks>
std::int64_t insert_by_chunks(E& ex, std::int32_t m, std::int32_t* order, Ins& one, Hooks& h,
                              const Schedule& how = Schedule{}) {
  const int sample_level = how.sample_level, parts_per_thread = how.parts_per_thread;
  const int alone_level = how.alone_level;
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
  // Each thread then runs `then` (once no part is left to take).
  auto each_part_as_free = [&](std::int64_t parts, auto f, auto then) {
    const std::int64_t shares = std::min<std::int64_t>(parts, nt);
    const std::int64_t per = (parts + shares - 1) / shares;
    std::atomic<std::int64_t> taken{0};
    ex.team([&](const auto&) {
      for (std::int64_t i; (i = taken.fetch_add(1, std::memory_order_relaxed)) < shares * per;) {
        const std::int64_t c = (i % shares) * per + i / shares;
        if (c < parts) f(c);
      }
      then();
    });
  };
  each_chunk([&](std::int64_t c) {
    std::int32_t lo, hi;
    bounds(c, lo, hi);
    order_by_level(lo, hi, skip, order, counts.data() + c * kLevels, how.level_bits);
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
  // The threads, each over its part's points (spans[c], in order), its inserter a copy of
  // `split` (which knows the parts: Ins::owner); those that must wait go to wait[c]. Where parts
  // are split, a part split off is numbered from `parts` on, and its waiting points join those
  // of the given part its points came from.
  auto most_parts = [&](std::int64_t parts) {
    return how.locks ? parts + kSplitsPerThread * nt : parts;
  };
  auto threads = [&](std::int64_t parts, const Ins& split, std::uint32_t round,
                     std::vector<PartPoints::Span> spans,
                     std::vector<std::vector<std::int32_t>>& wait) {
    const std::int64_t cap = most_parts(parts);
    PartPoints P(std::move(spans), cap);
    wait.assign(std::size_t(cap), {});
    auto ready = [&](Ins& mine, std::int64_t c) {
      mine = split;
      mine.own = std::int32_t(c);
      mine.rng += std::uint32_t(c) + round;  // (each part and round walks its own way)
    };
    auto insert_part = [&](Ins& mine, std::int64_t c) {
      std::vector<std::int32_t>& w = wait[std::size_t(c)];
      const std::int32_t* at = P.span[std::size_t(c)].at;
      if (how.locks) {
        for (std::int64_t i; (i = P.take(c)) >= 0;)
          if (!mine.insert(at[i])) w.push_back(at[i]);
        // (a point waits where another thread held what its cavity needed at that moment; by
        // now that thread mostly works elsewhere: 3D uniform 10^6 on 16 threads, 440-800 points
        // were left to wait, now 0-3; on a grid 1 500-3 000, now 90-420, mostly on the hull's
        // planes, whose cavities are large)
        std::size_t kept = 0;
        for (const std::int32_t q : w)
          if (!mine.insert(q)) w[kept++] = q;
        w.resize(kept);
      } else {  // (nothing is split: the part's thread alone takes its points)
        for (std::int64_t i = 0; i < P.span[std::size_t(c)].n; ++i)
          if (!mine.insert(at[i])) w.push_back(at[i]);
      }
      h.leave(mine, c);
    };
    each_part_as_free(
        parts,
        [&](std::int64_t c) {
          Ins mine = split;
          ready(mine, c);
          h.enter(mine, c);
          insert_part(mine, c);
        },
        [&] {
          if (!how.locks) return;
          for (;;) {
            Ins mine = split;
            const std::int64_t id =
                P.split_off(kMinSplit, [&](std::int64_t c, std::int64_t root, std::int64_t n) {
                  ready(mine, c);
                  return h.enter_split(mine, c, root, n);
                });
            if (id < 0) break;
            insert_part(mine, id);
          }
        });
    const std::int64_t made = std::min(P.made.load(), cap);
    for (std::int64_t c = parts; c < made; ++c) {
      if (P.span[std::size_t(c)].root < 0) continue;  // (numbered, but no room was found for it)
      std::vector<std::int32_t>& to = wait[std::size_t(P.span[std::size_t(c)].root)];
      const std::vector<std::int32_t>& w = wait[std::size_t(c)];
      to.insert(to.end(), w.begin(), w.end());
    }
    wait.resize(std::size_t(parts));
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
    h.threads_begin(sizes, split, most_parts(std::int64_t(sizes.size())));
    std::vector<PartPoints::Span> spans(static_cast<std::size_t>(nc));
    for (std::int64_t c = 0; c < nc; ++c)  // (a chunk's levels lie in order, highest first)
      spans[std::size_t(c)] = {order + begin[c * kLevels + hi - 1], sizes[std::size_t(c)]};
    const std::int64_t w = threads(nc, split, 0, std::move(spans), waiting);
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
    h.threads_begin(sizes, split, most_parts(std::int64_t(sizes.size())));
    const std::int64_t given = waited;
    std::vector<PartPoints::Span> spans(static_cast<std::size_t>(parts));
    for (std::int64_t c = 0; c < parts; ++c)
      spans[std::size_t(c)] = {by_owner[std::size_t(c)].data(), sizes[std::size_t(c)]};
    waited = threads(parts, split, std::uint32_t(r) * std::uint32_t(m), std::move(spans), waiting);
    h.threads_done(given - waited);
    h.mark("rounds");
    if (8 * (given - waited) < given) break;
  }
  // The points still waiting, in curve order, on one thread, each walk from the last
  // insertion's simplex.
  for (std::int64_t c = 0; c < std::int64_t(waiting.size()); ++c) {
    std::vector<std::int32_t>& wait = waiting[std::size_t(c)];
    std::sort(wait.begin(), wait.end());
    for (const std::int32_t q : wait) h.put(one, c, q);
  }
  h.mark("deferred");
  return sample_waited + waited;
}

}  // namespace gpugeom::mesh::cavities
