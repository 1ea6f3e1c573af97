// Segment recovery in parallel rounds, one algorithm for both executors; included inside
// gpugeom::cdt::{cpu,cuda}_impl after `using Exec = ...`.
//
// The segments are first reduced on the executor (ends mapped through duplicate_of; zero-length
// and repeated ones dropped, the first of each kept). Each segment then keeps a frontier, the
// input point up to which it is already a chain of edges. A round:
//   1. every segment advances its frontier along edges that lie on it, marking them;
//   2. each unfinished one walks its next piece's cavity (cavity.hpp) and claims its triangles
//      and the triangles beside them with its priority (a fixed scramble of its number; an
//      atomic maximum per triangle); a walk that meets an edge already on a segment means the
//      two segments cross: the recovery stops and reports the pair (the smallest, for a
//      deterministic message; the caller refuses or splits them);
//   3. a segment that holds every claim it made wins;
//   4. winners rebuild their cavities at once (no two share a triangle or its neighbour).
// The segment with the highest priority among the unfinished always wins, so every round makes
// progress, and which segments win depends only on the mesh: the result never depends on
// timing. Each rebuild leaves the triangulation constrained Delaunay (cavity.hpp), so nothing is
// flipped afterwards.

struct RoundCounters {
  std::uint64_t cross;  // smallest (walker << 32 | crossed segment) of a crossing; ~0: none
  std::int64_t broken;  // walks or rebuilds that found the triangulation broken
  std::int64_t winners, ints, used;
  std::int64_t pieces;  // pieces found already edges and marked
  std::int64_t cavity_triangles, antennas;
};

GG_INLINE std::uint64_t claim_key(std::int32_t id) {
  std::uint32_t h = std::uint32_t(id) * 0x9E3779B1u;  // a bijection of 32 bits
  h ^= h >> 16;
  h *= 0x85EBCA6Bu;
  h ^= h >> 13;
  return (std::uint64_t(h) << 32) | (std::uint32_t(id) + 1u);  // unique, never 0
}

struct ClaimVisitor {
  std::uint64_t* claim;
  std::uint64_t key;
  GG_HD void triangle(std::int32_t t) { atomic_max(claim + t, key); }
  GG_HD void left(std::int32_t, std::int32_t, std::int32_t out, std::int32_t) {
    if (out >= 0) atomic_max(claim + out, key);
  }
  GG_HD void right(std::int32_t x, std::int32_t y, std::int32_t out, std::int32_t g) {
    left(x, y, out, g);
  }
};

struct OwnVisitor {
  const std::uint64_t* claim;
  std::uint64_t key;
  bool own = true;
  GG_HD void triangle(std::int32_t t) { own = own && claim[t] == key; }
  GG_HD void left(std::int32_t, std::int32_t, std::int32_t out, std::int32_t) {
    if (out >= 0) own = own && claim[out] == key;
  }
  GG_HD void right(std::int32_t x, std::int32_t y, std::int32_t out, std::int32_t g) {
    left(x, y, out, g);
  }
};

// segs: nseg pairs in executor memory; dup: duplicate_of in executor memory (n entries); the
// mesh m (nt triangles, seg all -1) is made the constrained Delaunay triangulation.
inline void recover_segments(Exec& ex, const MeshView& m, std::int64_t nt, const std::int32_t* segs,
                             std::int64_t nseg, const std::int32_t* dup, RecoveryCounts& rc) {
  using u64 = std::uint64_t;
  constexpr u64 kNone = ~u64(0);
  const std::int64_t max_steps = 3 * nt + 3;
  // ---- the segments: ends through dup, zero-length and repeated ones dropped ----
  auto keys = ex.template alloc<u64>(std::size_t(std::max<std::int64_t>(nseg, 1)));
  auto order = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(nseg, 1)));
  {
    u64* kp = keys.data();
    std::int32_t* op = order.data();
    ex.for_each_index(
        nseg, GG_LAMBDA(std::int64_t k) {
          std::int32_t a = segs[2 * k], b = segs[2 * k + 1];
          if (dup[a] >= 0) a = dup[a];  // the point used for a repeated one
          if (dup[b] >= 0) b = dup[b];
          kp[k] = a == b ? kNone : (u64(a < b ? a : b) << 32 | std::uint32_t(a < b ? b : a));
          op[k] = std::int32_t(k);
        });
  }
  ex.sort_by_key(keys.data(), order.data(), nseg);  // stable: the first of equal ones first
  auto pos = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(nseg, 1)));
  const u64* kp = keys.data();
  const std::int64_t kept = ex.compact_indices(
      nseg, GG_LAMBDA(std::int64_t j) { return kp[j] != kNone && (j == 0 || kp[j] != kp[j - 1]); },
      pos.data());
  {
    auto zero = ex.template alloc<std::int64_t>(1);
    ex.transform_reduce_into(
        nseg, GG_LAMBDA(std::int64_t j)->std::int64_t { return kp[j] == kNone ? 1 : 0; },
        std::int64_t(0), thrust::plus<std::int64_t>(), zero.data());
    ex.to_host(zero.data(), 1, &rc.zero_length);
  }
  rc.kept = kept;
  rc.repeated = nseg - rc.zero_length - kept;
  if (kept == 0) return;
  const std::size_t K = std::size_t(kept);
  auto sa = ex.template alloc<std::int32_t>(K), sb = ex.template alloc<std::int32_t>(K),
       sid = ex.template alloc<std::int32_t>(K), su = ex.template alloc<std::int32_t>(K),
       wt = ex.template alloc<std::int32_t>(K), wi = ex.template alloc<std::int32_t>(K),
       cnt = ex.template alloc<std::int32_t>(K), act = ex.template alloc<std::int32_t>(K),
       act2 = ex.template alloc<std::int32_t>(K), win = ex.template alloc<std::int32_t>(K);
  auto rec = ex.template alloc<std::int8_t>(K);
  std::int32_t *A = sa.data(), *B = sb.data(), *ID = sid.data(), *U = su.data(), *WT = wt.data(),
               *WI = wi.data(), *CNT = cnt.data(), *WIN = win.data();
  std::int8_t* REC = rec.data();
  {
    const std::int32_t *P = pos.data(), *O = order.data();
    std::int32_t* act0 = act.data();
    ex.for_each_index(
        kept, GG_LAMBDA(std::int64_t r) {
          const std::int32_t k = O[P[r]];
          std::int32_t a = segs[2 * std::int64_t(k)], b = segs[2 * std::int64_t(k) + 1];
          if (dup[a] >= 0) a = dup[a];
          if (dup[b] >= 0) b = dup[b];
          A[r] = a, B[r] = b, ID[r] = k, U[r] = a, REC[r] = 0;
          act0[r] = std::int32_t(r);
        });
  }
  keys = {}, order = {}, pos = {};
  // ---- a triangle of each vertex ----
  ex.for_each_index(
      3 * nt, GG_LAMBDA(std::int64_t i) { m.vt[m.tri[i]] = std::int32_t(i / 3); });
  auto claim = ex.template alloc<u64>(std::size_t(nt));
  auto ctr = ex.template alloc<RoundCounters>(1);
  RoundCounters* C = ctr.data();
  ex.for_each_index(
      1, GG_LAMBDA(std::int64_t) { *C = RoundCounters{kNone, 0, 0, 0, 0, 0, 0, 0}; });
  u64* CL = claim.data();
  ScratchSlots<Exec> slots(ex, std::int64_t(1) << 16, pred::kIncircleScratch,
                           std::size_t(64) << 20);
  typename Exec::template Buffer<std::int32_t> ints;
  std::int64_t nact = kept, rebuilt = 0;
  RoundCounters h{};
  // Reads the round's counters; false when a walk met a segment's edge (two segments cross:
  // reported in rc, the recovery stops).
  auto read_counters = [&]() {
    ex.to_host(C, 1, &h);
    if (h.broken)
      throw Error(ErrorCode::Internal, "cdt2d: " + std::to_string(h.broken) +
                                           " segment walks found the triangulation broken");
    if (h.cross == kNone) return true;
    const std::int32_t s1 = std::int32_t(h.cross >> 32), s2 = std::int32_t(std::uint32_t(h.cross));
    rc.cross_a = std::min(s1, s2), rc.cross_b = std::max(s1, s2);
    return false;
  };
  for (std::int64_t round = 0; nact > 0; ++round) {
    std::int32_t* L = act.data();
    // 1. Frontiers along the edges already on their segments.
    ex.for_each_index(
        nact, GG_LAMBDA(std::int64_t j) {
          const std::int32_t r = L[j], a = A[r], b = B[r];
          std::int32_t u = U[r];
          std::int64_t marked = 0;
          while (u != b) {
            const Wedge wd = find_wedge(m, a, b, u, max_steps);
            if (wd.t < 0) {
              atomic_add(&C->broken, std::int64_t(1));
              break;
            }
            if (wd.v < 0) {
              WT[r] = wd.t, WI[r] = wd.iu;
              break;
            }
            mark_edge(m, wd.t, wd.k, ID[r]);
            ++marked;
            u = wd.v;
          }
          U[r] = u;
          if (marked) atomic_add(&C->pieces, marked);
        });
    nact = ex.copy_if(
        L, nact, act2.data(), GG_LAMBDA(std::int32_t r) { return U[r] != B[r]; });
    std::swap(act, act2);
    L = act.data();
    if (nact == 0) break;
    rc.rounds = round + 1;
    // 2. Claims.
    ex.fill(CL, nt, u64(0));
    ex.for_each_index(
        nact, GG_LAMBDA(std::int64_t j) {
          const std::int32_t r = L[j];
          const Wedge wd{WT[r], -1, WI[r], 0};
          ClaimVisitor vis{CL, claim_key(ID[r])};
          const WalkEnd e = walk_piece(m, A[r], B[r], U[r], wd, max_steps, vis);
          CNT[r] = e.count;
          if (e.status == kWalkCrosses)
            atomic_min(&C->cross, u64(std::uint32_t(ID[r])) << 32 | std::uint32_t(e.other));
          else if (e.status != kWalkOk)
            atomic_add(&C->broken, std::int64_t(1));
        });
    // 3. Winners.
    ex.for_each_index(
        1, GG_LAMBDA(std::int64_t) { C->winners = 0, C->ints = 0, C->used = 0; });
    ex.for_each_index(
        nact, GG_LAMBDA(std::int64_t j) {
          const std::int32_t r = L[j];
          const Wedge wd{WT[r], -1, WI[r], 0};
          OwnVisitor vis{CL, claim_key(ID[r])};
          const WalkEnd e = walk_piece(m, A[r], B[r], U[r], wd, max_steps, vis);
          if (e.status != kWalkOk || !vis.own) return;
          WIN[atomic_add(&C->winners, std::int64_t(1))] = r;
          atomic_add(&C->ints, cavity_ints(CNT[r]));
        });
    if (!read_counters()) return;
    if (h.winners == 0)  // (the highest priority always wins: a broken triangulation)
      throw Error(ErrorCode::Internal, "cdt2d: no segment cavity could be claimed");
    rebuilt += h.winners;
    if (std::int64_t(ints.size()) < h.ints)
      ints = ex.template alloc<std::int32_t>(std::size_t(h.ints + h.ints / 4));
    // 4. Rebuilds.
    std::int32_t* I = ints.data();
    slots.run(
        ex, h.winners, GG_LAMBDA(std::int64_t j, double* s) {
          const std::int32_t r = WIN[j];
          const Wedge wd{WT[r], -1, WI[r], 0};
          const std::int64_t need = cavity_ints(CNT[r]);
          std::int32_t* at = I + atomic_add(&C->used, need);
          std::int32_t antennas = 0;
          const std::int32_t w = rebuild_cavity(m, A[r], B[r], U[r], wd, ID[r], CNT[r], max_steps,
                                                CL, at, s, antennas);
          if (w < 0) {
            atomic_add(&C->broken, std::int64_t(1));
            return;
          }
          U[r] = w, REC[r] = 1;
          atomic_add(&C->cavity_triangles, std::int64_t(CNT[r]));
          if (antennas) atomic_add(&C->antennas, std::int64_t(antennas));
        });
  }
  if (!read_counters()) return;
  rc.pieces = h.pieces + rebuilt;  // (each rebuild made one piece an edge)
  rc.cavity_triangles = h.cavity_triangles;
  rc.antennas = h.antennas;
  {
    auto got = ex.template alloc<std::int64_t>(1);
    ex.transform_reduce_into(
        kept, GG_LAMBDA(std::int64_t r)->std::int64_t { return REC[r]; }, std::int64_t(0),
        thrust::plus<std::int64_t>(), got.data());
    ex.to_host(got.data(), 1, &rc.recovered);
  }
}
