// Point location by walks, for a triangulation that starts from a given one rather than from a
// first simplex (delaunay2d: the digital method's sketch and DynamicDelaunay2d's kept
// triangulation; delaunay3d: DynamicDelaunay3d's kept tetrahedralisation). Each point walks from
// a simplex near it towards itself, leaving each simplex across a face it lies strictly beyond.
//
// The face a walk tries first is drawn by hashing (point, step): a walk that always prefers the
// same face can cycle in a triangulation that is not Delaunay (a start's: a few such points each
// cost a walk of every slot, then a scan of them all, seconds at 10^7); drawn, it ends with
// probability one (the stochastic walk). A walk is still bounded by the slots in use, and one
// that reaches the bound scans every slot, so that location ends on any store.
#pragma once
#include <cstdint>

#include "base/hd.hpp"
#include "exec/atomics.hpp"
#include "mesh/priority.hpp"

namespace gpugeom::mesh {

// How the walks went: steps taken, walks that ended in the scan, the longest walk.
struct WalkCounts {
  std::int64_t steps = 0, scans = 0, longest = 0;
};

// Every point q < m located: loc[q] = base + the position of a slot whose simplex holds it,
// -1 where from(q) says q is a vertex of the start (-2), or where no slot holds it (then *lost
// counts it, an internal error the caller reports).
//
// Store (K faces a simplex; positions 0 .. slots - 1):
//   `using Simplex`, `Simplex at(std::int64_t t)`,
//   `bool beyond(const Simplex&, int k, std::int32_t q)`: q strictly beyond face k,
//   `std::int64_t across(const Simplex&, int k)`: the position of the neighbour over face k,
//   `bool holds(std::int64_t t, std::int32_t q)`: the scan's test (false for a dead slot).
// from(q): the position q's walk starts at, -1 for none (the scan alone), -2 for a vertex.
template <int K, class Exec, class Store, class From>
WalkCounts locate_by_walks(Exec& ex, std::int64_t m, std::int64_t slots, const Store& S, From from,
                           std::int32_t base, std::int32_t* loc, std::int64_t* lost) {
  auto counts = ex.template alloc<std::int64_t>(3);
  std::int64_t* ws = counts.data();
  ex.fill(ws, 3, std::int64_t(0));
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t i) {
        const std::int32_t q = std::int32_t(i);
        std::int64_t t = from(q);
        if (t == -2) {
          loc[q] = -1;
          return;
        }
        for (std::int64_t step = 0; t >= 0 && step <= slots; ++step) {
          const typename Store::Simplex T = S.at(t);
          int leave = -1;
          const int r = int(scatter(std::uint32_t(q) * 2654435761u + std::uint32_t(step)) % K);
          for (int j = 0; j < K && leave < 0; ++j)
            if (S.beyond(T, (r + j) % K, q)) leave = (r + j) % K;
          if (leave < 0) {
            loc[q] = base + std::int32_t(t);
            atomic_add(&ws[0], step);
            atomic_max(&ws[2], step);
            return;
          }
          t = S.across(T, leave);
        }
        atomic_add(&ws[1], std::int64_t(1));
        for (t = 0; t < slots; ++t)
          if (S.holds(t, q)) {
            loc[q] = base + std::int32_t(t);
            return;
          }
        loc[q] = -1;
        atomic_add(lost, std::int64_t(1));
      });
  std::int64_t w[3];
  ex.to_host(ws, 3, w);
  return WalkCounts{w[0], w[1], w[2]};
}

// The counts into a run's statistics (Delaunay2dStats, Delaunay3dStats: their fields).
template <class S>
void put_walk_counts(S& st, const WalkCounts& w) {
  st.start_walk_steps = w.steps;
  st.start_walk_scans = w.scans;
  st.start_walk_longest = w.longest;
}

}  // namespace gpugeom::mesh
