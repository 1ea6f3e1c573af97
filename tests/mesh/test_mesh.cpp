// The shared mesh pieces on the CPU executor: adjacency encoding, priority bijection,
// undecided markers, work lists, flip history, output compaction, input preparation, and the
// exact stages' scratch slots. (delaunay2d's and hull3d's suites run them on both executors.)
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cuda/atomic>
#include <map>
#include <random>
#include <set>
#include <thread>
#include <unordered_set>
#include <vector>

#include "base/clock.hpp"
#include "exec/cpu_exec.hpp"
#include "exec/scratch_slots.hpp"
#include "mesh/adjacency.hpp"
#include "mesh/cavity_schedule.hpp"
#include "delaunay3d/tet.hpp"
#include "mesh/compact.hpp"
#include "mesh/decision.hpp"
#include "mesh/history.hpp"
#include "mesh/prepare.hpp"
#include "mesh/priority.hpp"
#include "mesh/work_list.hpp"

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

TEST(MeshDecision, UndecidedMarksAreApartFromDecisions) {
  for (int k = 0; k <= mesh::kMaxUndecidedFace; ++k) {
    const int d = mesh::undecided_at(k);
    EXPECT_TRUE(mesh::is_undecided(d));
    EXPECT_EQ(mesh::undecided_face(d), k);
    EXPECT_EQ(std::int8_t(d), d);  // fits the int8 decision arrays
  }
  for (int d = -1; d < 100; ++d) EXPECT_FALSE(mesh::is_undecided(d));
}

TEST(MeshWorkLists, RoundsAlternateListsAndLengths) {
  std::int32_t a[1], b[1];
  std::int64_t len[2];
  const mesh::WorkLists L{{a, b}, len};
  for (std::int32_t r = 0; r < 6; ++r) {
    EXPECT_EQ(L.current(r), r % 2 ? b : a);
    EXPECT_EQ(L.next(r), L.current(r + 1));
    EXPECT_EQ(L.next_count(r), L.count(r + 1));
    EXPECT_NE(L.count(r), L.next_count(r));
  }
}

// The flip log against a replay: points in slots, flips rewriting random pairs of slots, each
// point of a flipped slot going to the side its position picks against the flip's payload.
TEST(MeshFlipLog, FollowMatchesAReplayAcrossEpochs) {
  constexpr int kSlots = 64, kPoints = 500;
  using Log = mesh::FlipLog<2, 2>;
  std::mt19937 rng(11);
  std::vector<mesh::FlipHist> hist(kSlots, mesh::FlipHist{-1, -1});
  Log log{nullptr, hist.data(), 0};
  std::vector<std::int32_t> where(kPoints), pos(kPoints);
  for (int q = 0; q < kPoints; ++q) where[q] = std::int32_t(rng() % kSlots), pos[q] = q;
  for (int epoch = 0; epoch < 5; ++epoch) {
    const int flips = 1 + int(rng() % 300);
    std::vector<std::int32_t> rec(std::size_t(Log::kStride) * flips);
    log.rec = rec.data();
    std::vector<std::int32_t> start = where;
    for (int f = 0; f < flips; ++f) {
      const std::int32_t s0 = std::int32_t(rng() % kSlots);
      std::int32_t s1 = std::int32_t(rng() % kSlots);
      if (s1 == s0) s1 = (s1 + 1) % kSlots;
      const std::int32_t cut = std::int32_t(rng() % kPoints);
      const std::int32_t slots[2] = {s0, s1};
      mesh::FlipHist h[2];
      log.load(slots, h);
      log.append(log.base + f, slots, {cut, 0}, h);
      for (int q = 0; q < kPoints; ++q)
        if (where[q] == s0 || where[q] == s1) where[q] = pos[q] > cut ? s1 : s0;
    }
    for (int q = 0; q < kPoints; ++q) {
      const auto side = [&](const std::int32_t* payload) { return pos[q] > payload[0] ? 1 : 0; };
      ASSERT_EQ(log.follow(start[q], side), where[q]) << "epoch " << epoch << " point " << q;
    }
    // A new epoch: the old records are stale without clearing the per-slot entries.
    if (log.next_epoch(flips, flips)) std::fill(hist.begin(), hist.end(), mesh::FlipHist{-1, -1});
    for (int s = 0; s < kSlots; ++s)
      ASSERT_EQ(log.follow(s, [](const std::int32_t*) { return 0; }), s);
  }
  // Near the top of the record numbers the caller is told to clear and start again at 0.
  log.base = (INT32_MAX >> Log::kSideBits) - 100;
  EXPECT_TRUE(log.next_epoch(10, 1000));
  EXPECT_EQ(log.base, 0);
}

// A store of five slots, two of them not live, as compact_live reads it (neighbour slots, as
// each store decodes its own encoding).
struct ToyStore {
  GG_HD bool live(std::int64_t t) const { return t != 1 && t != 3; }
  GG_HD mesh::SimplexRecord<3> get(std::int64_t t) const {
    mesh::SimplexRecord<3> r;
    for (int k = 0; k < 3; ++k) {
      r.v[k] = std::int32_t(10 * t + k);
      r.n[k] = std::int32_t((t + k + 1) % 5);  // slots t+1, t+2, t+3
    }
    return r;
  }
};
// The wide reading of the encoding (delaunay2d) round-trips every slot below 2^30 and every
// local index, the top slots included, where the signed reading would turn negative.
TEST(MeshAdjacency, WideEncodingRoundTrips) {
  using W = mesh::WideAdjacency;
  for (std::int64_t s : {std::int64_t(0), std::int64_t(1), (std::int64_t(1) << 29) - 1,
                         std::int64_t(1) << 29, W::kMaxSlots - 2, W::kMaxSlots - 1})
    for (int k = 0; k < 4; ++k) {
      const std::int32_t e = W::enc(std::int32_t(s), k);
      EXPECT_EQ(W::simplex_of(e), s);
      EXPECT_EQ(W::loc_of(e), k);
      if (s < (std::int64_t(1) << 29)) {
        EXPECT_EQ(e, mesh::enc(std::int32_t(s), k));  // the same bits where both apply
      }
    }
}

// delaunay3d's store reads the encoding wide, with -1 for "no neighbour": its last slot,
// kMaxTetSlots - 1, never encodes to -1 (the slot above it would, at face 3).
TEST(MeshAdjacency, TetStoreKeepsMinusOneFree) {
  for (std::int64_t s : {std::int64_t(0), del3d::kMaxTetSlots - 1})
    for (int k = 0; k < 4; ++k) {
      EXPECT_NE(del3d::enc(std::int32_t(s), k), del3d::kNoNeighbour);
      EXPECT_EQ(del3d::simplex_of(del3d::enc(std::int32_t(s), k)), s);
    }
  EXPECT_EQ(del3d::enc(std::int32_t(del3d::kMaxTetSlots), 3), del3d::kNoNeighbour);
}

TEST(MeshCompact, LiveSimplicesRenumberedWithTheirNeighbours) {
  CpuExec ex;
  const auto c = mesh::compact_live<3>(ex, 5, ToyStore{});
  ASSERT_EQ(c.count, 3);
  // live slots 0, 2, 4 become 0, 1, 2; neighbours in slots 1 and 3 become -1
  const std::vector<std::int32_t> v(c.simplices.data(), c.simplices.data() + 9),
      n(c.neighbors.data(), c.neighbors.data() + 9);
  EXPECT_EQ(v, (std::vector<std::int32_t>{0, 1, 2, 20, 21, 22, 40, 41, 42}));
  EXPECT_EQ(n, (std::vector<std::int32_t>{-1, 1, -1, -1, 2, 0, 0, -1, 1}));
}

TEST(MeshPrepare, ExtremesAndValidation) {
  CpuExec ex;
  const std::vector<double> p = {1, 2, 0, 5, 1, 2, -3, 9, 1, 2, -3, 9, 7, 7, 0, 5};
  const auto e = mesh::extremes<2>(ex, p.data(), 8);
  EXPECT_EQ(e.bad, 0);
  EXPECT_EQ(e.lo.i, 3);  // (-3, 9) first seen at 3, again at 5: the smaller index
  EXPECT_EQ(e.hi.i, 6);
  std::vector<double> q = p;
  q[5] = std::numeric_limits<double>::quiet_NaN();
  q[8] = 1e300;
  EXPECT_EQ(mesh::extremes<2>(ex, q.data(), 8).bad, 2);
  q[9] = -0.0;
  const auto b = mesh::bounds_in_place<2>(ex, q.data(), 8);
  EXPECT_EQ(b.bad, 2);
  EXPECT_FALSE(std::signbit(q[9]));  // -0 became +0
  EXPECT_EQ(b.lo[0], -3);
  EXPECT_EQ(b.hi[1], 9);
}

// side: the lattice's points per axis (few: long runs of duplicates, sorted by passes over
// everything; more: short runs, each sorted alone).
template <int D>
void sorted_distinct_case(std::int64_t n, std::uint32_t seed, int side = 16) {
  CpuExec ex;
  std::mt19937 rng(seed);
  std::vector<double> p(std::size_t(D * n));
  for (auto& x : p) x = double(rng() % side) * 0.25 - 1.0;  // a coarse lattice: duplicates
  const std::vector<double> input = p;
  const auto box = mesh::bounds_in_place<D>(ex, p.data(), n);
  ASSERT_EQ(box.bad, 0);
  const auto S = mesh::sort_distinct<D>(ex, p.data(), n, box);
  // the first index of each distinct point, by brute force
  std::map<std::vector<double>, std::int32_t> first;
  for (std::int64_t i = 0; i < n; ++i)
    first.emplace(std::vector<double>(&input[D * i], &input[D * i] + D), std::int32_t(i));
  ASSERT_EQ(S.m, std::int64_t(first.size()));
  ASSERT_EQ(S.duplicates, n - S.m);
  spatial::Box sb{};
  for (int d = 0; d < D; ++d) sb.lo[d] = box.lo[d], sb.hi[d] = box.hi[d];
  std::set<std::int32_t> kept;
  for (std::int64_t i = 0; i < S.m; ++i) {
    const std::int32_t o = S.orig.data()[i];
    const std::vector<double> x(&S.pts.data()[D * i], &S.pts.data()[D * i] + D);
    EXPECT_EQ(x, std::vector<double>(&input[D * o], &input[D * o] + D));
    EXPECT_EQ(first.at(x), o);  // the kept copy is the one of smallest index
    kept.insert(o);
    if (i > 0) {
      const auto k0 = spatial::hilbert_key<D>(&S.pts.data()[D * (i - 1)], sb),
                 k1 = spatial::hilbert_key<D>(&S.pts.data()[D * i], sb);
      EXPECT_LE(k0, k1);
      if (k0 == k1)  // (points sharing a curve cell: by their coordinates)
        EXPECT_LT(std::vector<double>(&S.pts.data()[D * (i - 1)], &S.pts.data()[D * i]), x);
    }
  }
  EXPECT_EQ(std::int64_t(kept.size()), S.m);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int32_t o = first.at(std::vector<double>(&input[D * i], &input[D * i] + D));
    EXPECT_EQ(S.dup.data()[i], o == i ? -1 : o);
  }
}
TEST(MeshPrepare, SortedDistinctPoints2d) {
  sorted_distinct_case<2>(3000, 3);
}
TEST(MeshPrepare, SortedDistinctPoints3d) {
  sorted_distinct_case<3>(20000, 4);
}
TEST(MeshPrepare, SortedDistinctPointsLongRuns) {
  sorted_distinct_case<2>(3000, 5, 3);
  sorted_distinct_case<3>(5000, 6, 2);
}
// Points closer than a curve cell share keys without being equal: each run in coordinate order.
TEST(MeshPrepare, SortedDistinctPointsSharingCells) {
  CpuExec ex;
  const std::int64_t n = 4000;
  std::mt19937 rng(7);
  std::vector<double> p(std::size_t(2 * n));
  for (std::int64_t i = 0; i < n; ++i) {  // clusters of points a few ulps apart
    const double c = double(rng() % 512) / 512;
    p[2 * i] = std::nextafter(c, 2.0) + double(rng() % 4) * 1e-16;
    p[2 * i + 1] = c * c + double(rng() % 4) * 1e-16;
  }
  p[0] = -1, p[1] = -1, p[2] = 2, p[3] = 2;  // (a box wide enough that cells hold several)
  const auto box = mesh::bounds_in_place<2>(ex, p.data(), n);
  const auto S = mesh::sort_distinct<2>(ex, p.data(), n, box);
  spatial::Box sb{};
  for (int d = 0; d < 2; ++d) sb.lo[d] = box.lo[d], sb.hi[d] = box.hi[d];
  std::int64_t shared = 0;
  for (std::int64_t i = 1; i < S.m; ++i) {
    const double *a = &S.pts.data()[2 * (i - 1)], *b = &S.pts.data()[2 * i];
    if (spatial::hilbert_key<2>(a, sb) != spatial::hilbert_key<2>(b, sb)) continue;
    ++shared;
    ASSERT_TRUE(a[0] < b[0] || (a[0] == b[0] && a[1] < b[1])) << i;
  }
  EXPECT_GT(shared, 100);
}

TEST(ScratchSlots, EveryItemOnceOnItsOwnSlot) {
  CpuExec ex;
  const ScratchSlots<CpuExec> slots(ex, 7, 16);
  EXPECT_EQ(slots.slots(), std::min<std::int64_t>(7, ex.concurrency()));
  EXPECT_EQ(ScratchSlots<CpuExec>(ex, 1000, 1000, 3 * 8000).slots(), 3);  // within the budget
  for (std::int64_t m : {0, 1, 5, 7, 8, 1001}) {
    std::vector<std::atomic<int>> hits(std::size_t(m + 1));
    const SlotView v = slots.view();
    slots.run(ex, m, [&](std::int64_t j, double* s) {
      const std::int64_t t = (s - v.base) / v.doubles;  // the slot, and its items stride
      EXPECT_EQ(j % std::min<std::int64_t>(m, v.slots), t);
      s[0] = double(j);
      hits[std::size_t(j)]++;
    });
    for (std::int64_t j = 0; j < m; ++j) ASSERT_EQ(hits[std::size_t(j)].load(), 1) << m;
  }
  // counted: the length read when the pass runs, once() on one slot
  std::int64_t len = 40;
  std::atomic<int> items{0}, once{0};
  slots.run_counted(
      ex, 100, CountAt{&len, 3}, [&](std::int64_t, double*) { items++; }, [&] { once++; });
  EXPECT_EQ(items.load(), 120);
  EXPECT_EQ(once.load(), 1);
}

// The parts' points of the CPU cavities' schedule (issue 53): taken from the front, the back
// half split off for an idle thread; every point is taken once, by the part it was given to or
// by one split off it.
TEST(MeshCavitySchedule, SplitTakesTheBackHalfOfThePartWithMostLeft) {
  std::vector<std::int32_t> pts(1000);
  for (std::size_t i = 0; i < pts.size(); ++i) pts[i] = std::int32_t(i);
  using Span = mesh::cavities::PartPoints::Span;
  mesh::cavities::PartPoints P({Span{pts.data(), 300}, Span{pts.data() + 300, 700}}, 4);
  for (int k = 0; k < 100; ++k) ASSERT_EQ(P.take(1), k);  // part 1: 600 left, part 0: 300
  std::int64_t asked = -1, root = -1;
  auto room = [&](std::int64_t id, std::int64_t r, std::int64_t n) {
    EXPECT_EQ(id, 2);
    root = r, asked = n;
    return true;
  };
  ASSERT_EQ(P.split_off(128, room), 2);
  EXPECT_EQ(root, 1);
  EXPECT_EQ(asked, 301);  // (room for half of what was left, and one)
  EXPECT_EQ(P.span[2].at, pts.data() + 300 + 400);
  EXPECT_EQ(P.span[2].n, 300);
  EXPECT_EQ(P.span[2].root, 1);
  for (int k = 0; k < 300; ++k) ASSERT_EQ(P.take(2), k);
  EXPECT_EQ(P.take(2), -1);
  for (int k = 100; k < 400; ++k) ASSERT_EQ(P.take(1), k);
  EXPECT_EQ(P.take(1), -1);  // (its back half went to part 2)
  // A split off part 0 (its 300 left); one of part 2 would be its root's, part 1's.
  ASSERT_EQ(P.split_off(128,
                        [&](std::int64_t, std::int64_t r, std::int64_t) {
                          EXPECT_EQ(r, 0);
                          return true;
                        }),
            3);
  // No room: nothing is split. Fewer left than asked: nothing either. No number left: -1.
  EXPECT_EQ(P.split_off(100, [](std::int64_t, std::int64_t, std::int64_t) { return false; }), -1);
  EXPECT_EQ(P.left[0].load(), std::uint64_t(150));
  EXPECT_EQ(P.split_off(151, room), -1);
  EXPECT_EQ(P.split_off(1, room), -1);  // (4 numbers, all used)
}

TEST(MeshCavitySchedule, EveryPointTakenOnceWhileThreadsSplit) {
  constexpr int kThreads = 8, kParts = 5;
  std::vector<std::int32_t> pts(200000);
  for (std::size_t i = 0; i < pts.size(); ++i) pts[i] = std::int32_t(i);
  for (int run = 0; run < 20; ++run) {
    using Span = mesh::cavities::PartPoints::Span;
    std::vector<Span> given;
    std::int64_t at = 0;
    for (int c = 0; c < kParts; ++c) {  // (uneven parts: the last is the largest)
      const std::int64_t n = c + 1 < kParts ? 1000 * (c + 1) : std::int64_t(pts.size()) - at;
      given.push_back(Span{pts.data() + at, n});
      at += n;
    }
    mesh::cavities::PartPoints P(given, kParts + 4 * kThreads);
    std::vector<std::atomic<int>> hits(pts.size());
    std::vector<std::atomic<int>> by_root(pts.size());
    std::atomic<int> next_part{0}, splits{0};
    auto insert_all = [&](std::int64_t c) {
      for (std::int64_t i; (i = P.take(c)) >= 0;) {
        const std::int32_t q = P.span[std::size_t(c)].at[i];
        hits[std::size_t(q)]++;
        by_root[std::size_t(q)] = int(P.span[std::size_t(c)].root);
      }
    };
    std::vector<std::thread> team;
    for (int t = 0; t < kThreads; ++t)
      team.emplace_back([&] {
        for (int c; (c = next_part++) < kParts;) insert_all(c);
        for (std::int64_t id; (id = P.split_off(16, [](std::int64_t, std::int64_t, std::int64_t) {
                                return true;
                              })) >= 0;) {
          splits++;
          insert_all(id);
        }
      });
    for (auto& t : team) t.join();
    for (std::size_t q = 0; q < pts.size(); ++q) {
      ASSERT_EQ(hits[q].load(), 1) << "point " << q << ", run " << run;
      std::int64_t root = 0, end = 0;
      while ((end += given[std::size_t(root)].n) <= std::int64_t(q)) ++root;
      ASSERT_EQ(by_root[q].load(), root) << "point " << q;
    }
    EXPECT_LE(splits.load(), 4 * kThreads);
  }
}
