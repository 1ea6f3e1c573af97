// The shifting phase on an executor (shift.hpp), included inside gpugeom::del2d::{cpu,cuda}_impl
// with Exec defined. Alg. 4.4 in rounds: a site is tested once every neighbour before it in a
// fixed scattered order (mesh::scatter of its index: no long chains on sorted input) has been,
// with the neighbours after it waiting for it, so no two neighbours move in one round and each
// test sees its neighbours where they are; on the boundary the two next boundary vertices on each
// side are neighbours too (the turns at p and q involve them). Alg. 4.5 in rounds: a bad site is
// deleted once no bad site before it within two edges is left, so the deletions of one round
// touch disjoint triangles; each re-triangulates its hole into its own fan's slots (ear clipping
// inside, the chain made convex on the boundary) and pairs the new half-edges with the ones
// around. The result is the same on every executor.

namespace digital_shifting {

constexpr int kGuard = 1 << 20;  // bounds every fan walk (a valid mesh never reaches it)

struct FanMesh {
  std::int32_t* tri;
  std::int32_t* twin;
  std::int8_t* alive;
  std::int32_t* some;
  GG_INLINE int corner(std::int32_t t, std::int32_t v) const {
    const std::int32_t* q = tri + 3 * std::int64_t(t);
    return q[0] == v ? 0 : (q[1] == v ? 1 : 2);
  }
  GG_INLINE std::int32_t at(std::int32_t t, int k) const {
    return tri[3 * std::int64_t(t) + k % 3];
  }
  // s's first triangle counter-clockwise (across its outgoing boundary edge; any where s is
  // inner): slot t, s at corner k. Returns whether s is on the boundary.
  GG_INLINE bool first(std::int32_t s, std::int32_t& t, int& k) const {
    t = some[s], k = corner(t, s);
    const std::int32_t t0 = t;
    for (int g = 0; g < kGuard; ++g) {
      const std::int32_t e = twin[3 * std::int64_t(t) + k];
      if (e < 0) return true;
      t = e / 3, k = corner(t, s);
      if (t == t0) return false;
    }
    return false;
  }
  // f(a, b, t, k) for each triangle (s, a, b) of s's fan, counter-clockwise, until it returns
  // false. Returns whether s is on the boundary.
  template <class F>
  GG_INLINE bool fan(std::int32_t s, F&& f) const {
    std::int32_t t;
    int k;
    const bool boundary = first(s, t, k);
    const std::int32_t t0 = t;
    for (int g = 0; g < kGuard; ++g) {
      if (!f(at(t, k + 1), at(t, k + 2), t, k)) break;
      const std::int32_t e = twin[3 * std::int64_t(t) + (k + 2) % 3];  // across (b -> s)
      if (e < 0 || e / 3 == t0) break;
      t = e / 3, k = corner(t, s);
    }
    return boundary;
  }
};

// One walk of s's star for the shifting test: tri(a, b) for each triangle (s, a, b) of its fan,
// and dep(u) for each vertex u whose position the test reads (the neighbours of s and, on the
// boundary, the next two boundary vertices on each side: the turns at its boundary neighbours
// involve them), each once and never s. The relation is symmetric (pred(pred(v)) = u exactly
// where succ(succ(u)) = v), so dep also lists the vertices whose tests read s. Returns whether
// s is on the boundary, and there p, q (its boundary neighbours: the last b, the first a) and
// pp, qq (theirs).
struct Ring {
  std::int32_t p = -1, q = -1, pp = -1, qq = -1;
};
template <class Tri, class Dep>
GG_INLINE bool star(const FanMesh& M, std::int32_t s, Tri&& tri, Dep&& dep, Ring& r) {
  const bool boundary = M.fan(s, [&](std::int32_t a, std::int32_t b, std::int32_t, int) {
    tri(a, b);
    dep(a);
    if (r.q < 0) r.q = a;
    r.p = b;
    return true;
  });
  if (!boundary) return false;
  dep(r.p);  // (the last b of a boundary fan is no a)
  M.fan(r.p, [&](std::int32_t, std::int32_t b, std::int32_t, int) {
    r.pp = b;
    return true;
  });
  std::int32_t t;
  int k;
  M.first(r.q, t, k);
  r.qq = M.at(t, k + 1);
  // (on a hull of three or four vertices they are s or its neighbours)
  auto seen = [&](std::int32_t u) {
    bool hit = u == s;
    M.fan(s, [&](std::int32_t a, std::int32_t b, std::int32_t, int) {
      hit |= a == u || b == u;
      return !hit;
    });
    return hit;
  };
  if (!seen(r.pp)) dep(r.pp);
  if (r.qq != r.pp && !seen(r.qq)) dep(r.qq);
  return true;
}

GG_INLINE bool before(std::int32_t u, std::int32_t v) {
  return mesh::scatter(std::uint32_t(u)) < mesh::scatter(std::uint32_t(v));
}

using digital::convex_turn;
using digital::orient;

constexpr std::int32_t kPending = std::numeric_limits<std::int32_t>::max();
constexpr std::int8_t kShifted = 1, kBad = 2;

}  // namespace digital_shifting

// The start on the executor: live triangles renumbered, their twins, and per point a start
// vertex near it (-1 for the start's own vertices and where none was found).
struct HeldStart {
  typename Exec::template Buffer<std::int32_t> tri, twin, hint;
  std::int64_t nt = 0;
};

// P: the n points in executor memory; sk: the frame; H: the sketch's arrays, consumed (the
// triangles are edited in place). Fills out's counts, phase times and reason (the start's
// whole check, on its boundary: shift.hpp); out's arrays stay empty (download_start).
inline HeldStart shift_on(Exec& ex, const double* P, std::int64_t n, const digital::Sketch& sk,
                          HeldSketch& H, digital::Start& out) {
  auto& phases = out.phase_ms;
  using namespace digital_shifting;
  auto t0 = std::chrono::steady_clock::now();
  auto phase = [&](const char* name) {
    ex.sync();
    const auto t1 = std::chrono::steady_clock::now();
    phases.push_back({name, std::chrono::duration<double, std::milli>(t1 - t0).count()});
    t0 = t1;
  };
  const std::int64_t nt = H.nt;
  auto d_alive = ex.template alloc<std::int8_t>(std::size_t(nt));
  auto d_some = ex.template alloc<std::int32_t>(std::size_t(n));
  auto d_pos = ex.template alloc<double>(std::size_t(2 * n));
  auto d_done = ex.template alloc<std::int32_t>(std::size_t(n));
  auto d_state = ex.template alloc<std::int8_t>(std::size_t(n));
  const FanMesh M{H.tri.data(), H.twin.data(), d_alive.data(), d_some.data()};
  double* pos = d_pos.data();
  const std::int32_t* pixel = H.pixel.data();
  std::int32_t* near = H.site_of.data();  // (from here: where a point's walk starts)
  std::int32_t* done = d_done.data();
  std::int8_t* state = d_state.data();
  ex.fill(M.alive, nt, std::int8_t(1));
  // A point's first triangle: the least slot that has it (by atomic minimum: a fan's walks and
  // so the holes' triangulations must not depend on which thread wrote last).
  ex.fill(M.some, n, kPending);
  ex.for_each_index(
      3 * nt, GG_LAMBDA(std::int64_t e) { atomic_min(&M.some[M.tri[e]], std::int32_t(e / 3)); });
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        if (M.some[i] == kPending) M.some[i] = -1;
      });
  // Every site starts at its grid point (exact: sketch.hpp); every point not in the sketch is
  // no one's neighbour and counts as done.
  const double ox = sk.ox, oy = sk.oy, h = sk.h;
  const std::int64_t w = sk.width;
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        const std::int64_t p = pixel[i];
        pos[2 * i] = ox + double(p % w) * h, pos[2 * i + 1] = oy + double(p / w) * h;
        done[i] = M.some[i] >= 0 ? kPending : -1;
        state[i] = 0;
      });
  auto list_a = ex.template alloc<std::int32_t>(std::size_t(n));
  auto list_b = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* la = list_a.data();
  std::int32_t* lb = list_b.data();
  phase("shift_setup");
  // Alg. 4.4 as a wavefront: a site is tested once every site whose position its test reads
  // (star) and that comes before it in the order has been, and those after it wait for it.
  // Each site counts its earlier dependencies; a tested site counts its later ones down, and a
  // site whose count reaches zero joins the next round's list (mesh::WorkLists: the rounds run
  // without the host, which reads the lengths once every few rounds). Within a round no two
  // sites depend on each other, so every test sees its dependencies where they end.
  auto d_wait = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* wait = d_wait.data();
  auto d_wl = ex.template alloc<std::int64_t>(4);  // both lists' lengths, rounds, tested
  std::int64_t* wl = d_wl.data();
  ex.fill(wl, 4, std::int64_t(0));
  ex.transform_reduce_into(
      n,
      GG_LAMBDA(std::int64_t i)->std::int64_t {
        const std::int32_t v = std::int32_t(i);
        std::int32_t c = 0;
        Ring ring;
        if (M.some[v] >= 0)
          star(
              M, v, [](std::int32_t, std::int32_t) {}, [&](std::int32_t u) { c += before(u, v); },
              ring);
        wait[v] = c;
        return M.some[v] >= 0;
      },
      std::int64_t(0), thrust::plus<std::int64_t>(), wl + 3);
  std::int64_t npend = 0;
  ex.to_host(wl + 3, 1, &npend);
  const std::int64_t ready = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return M.some[i] >= 0 && wait[i] == 0; }, la);
  ex.fill(wl, 1, ready);
  ex.fill(wl + 3, 1, std::int64_t(0));
  const mesh::WorkLists W{{la, lb}, wl};
  for (std::int32_t round = 0; npend > 0; ++round) {
    const std::int32_t r = round;
    std::int64_t* next_count = W.next_count(r);
    ex.fill(next_count, 1, std::int64_t(0));
    const std::int32_t* L = W.current(r);
    std::int32_t* next = W.next(r);
    ex.for_each_counted(
        W.count(r), npend, GG_LAMBDA(std::int64_t j) {
          const std::int32_t v = L[j];
          if (j == 0) atomic_max(wl + 2, std::int64_t(r) + 1);
          // (one walk: the test, and the later dependencies counted down, whose tests run in
          // a later round and read this one's position then)
          const double* own = P + 2 * std::int64_t(v);
          bool good = true;
          Ring ring;
          const bool boundary = star(
              M, v,
              [&](std::int32_t a, std::int32_t b) {
                good =
                    good && orient(own, pos + 2 * std::int64_t(a), pos + 2 * std::int64_t(b)) > 0;
              },
              [&](std::int32_t u) {
                if (before(v, u) && atomic_add(wait + u, std::int32_t(-1)) == 1)
                  next[append_slot(next_count)] = u;
              },
              ring);
          if (good && boundary) {
            const double *Pp = pos + 2 * std::int64_t(ring.p), *Pq = pos + 2 * std::int64_t(ring.q);
            good = convex_turn(pos + 2 * std::int64_t(ring.pp), Pp, own) &&
                   convex_turn(Pp, own, Pq) &&
                   convex_turn(own, Pq, pos + 2 * std::int64_t(ring.qq));
          }
          if (good) pos[2 * std::int64_t(v)] = own[0], pos[2 * std::int64_t(v) + 1] = own[1];
          state[v] = good ? kShifted : kBad;
          done[v] = r;
        });
    if (r % 4 == 3) {  // (the host looks every four rounds; a round past the last does nothing)
      std::int64_t len = 0;
      ex.to_host(W.count(r + 1), 1, &len);
      if (!len) break;
    }
    if (round > 100000) throw Error(ErrorCode::Internal, "shifting: the rounds do not end");
  }
  {
    ex.transform_reduce_into(
        n, GG_LAMBDA(std::int64_t i)->std::int64_t { return M.some[i] >= 0 && state[i] != 0; },
        std::int64_t(0), thrust::plus<std::int64_t>(), wl + 3);
    std::int64_t c[2];
    ex.to_host(wl + 2, 2, c);
    if (c[1] != npend)
      throw Error(ErrorCode::Internal, "shifting: " + std::to_string(npend - c[1]) +
                                           " site(s) never tested (dependencies not symmetric)");
    out.shift_rounds = c[0];
  }
  phase("shift_good");
  // Alg. 4.5: the bad sites, deleted in rounds (done[] now: the round of the deletion).
  std::int64_t nbad = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return state[i] == kBad; }, la);
  ex.for_each_index(
      nbad, GG_LAMBDA(std::int64_t j) { done[la[j]] = kPending; });
  auto d_len = ex.template alloc<std::int64_t>(std::size_t(n + 1));
  auto d_off = ex.template alloc<std::int64_t>(std::size_t(n + 1));
  std::int64_t* len = d_len.data();
  std::int64_t* off = d_off.data();
  auto d_cnt = ex.template alloc<std::int64_t>(3);
  std::int64_t* cnt = d_cnt.data();
  ex.fill(cnt, 3, std::int64_t(0));
  typename Exec::template Buffer<std::int32_t> scratch;  // (per round: link, slots, outer, work)
  auto d_mark = ex.template alloc<std::uint64_t>(std::size_t(n));
  std::uint64_t* mark = d_mark.data();
  ex.fill(mark, n, std::uint64_t(0));
  std::int32_t round = 0;
  while (nbad > 0) {
    const std::int32_t r = round;
    const std::int32_t* L = la;
    // Which go this round, and how long their links are. A bad site goes once no pending bad
    // site before it is within two edges: each pending one marks itself and its link vertices
    // with its key (the greatest wins: the round, so that older marks lose, then the complement
    // of its place in the order), and one whose own and link vertices' marks are all its own
    // key goes. (Two walks of its own fan instead of one of every link vertex's.)
    const std::uint64_t tag = std::uint64_t(r + 1) << 32;
    ex.for_each_index(
        nbad, GG_LAMBDA(std::int64_t j) {
          const std::int32_t b = L[j];
          const std::uint64_t key = tag | ~mesh::scatter(std::uint32_t(b));
          atomic_max(mark + b, key);
          std::int32_t last = -1;
          if (M.fan(b, [&](std::int32_t a, std::int32_t c, std::int32_t, int) {
                atomic_max(mark + a, key);
                last = c;
                return true;
              }))
            atomic_max(mark + last, key);
        });
    ex.for_each_index(
        nbad, GG_LAMBDA(std::int64_t j) {
          const std::int32_t b = L[j];
          const std::uint64_t key = tag | ~mesh::scatter(std::uint32_t(b));
          bool go = mark[b] == key;
          std::int64_t links = 0;
          std::int32_t last = -1;
          const bool boundary = M.fan(b, [&](std::int32_t a, std::int32_t c, std::int32_t, int) {
            ++links;
            go = go && mark[a] == key;
            last = c;
            return go;
          });
          if (boundary && go) go = mark[last] == key, ++links;
          len[j] = go ? links : 0;
        });
    ex.fill(len + nbad, 1, std::int64_t(0));
    ex.exclusive_scan(len, off, nbad + 1);
    std::int64_t total = 0;
    ex.to_host(off + nbad, 1, &total);
    if (std::int64_t(scratch.size()) < 4 * total)
      scratch = ex.template alloc<std::int32_t>(std::size_t(4 * total + 1024));
    std::int32_t* S0 = scratch.data();
    ex.for_each_index(
        nbad, GG_LAMBDA(std::int64_t j) {
          const std::int64_t k = off[j + 1] - off[j];
          if (!k) return;
          const std::int32_t b = L[j];
          std::int32_t* link = S0 + 4 * off[j];  // link vertices
          std::int32_t* slot = link + k;         // fan slots
          std::int32_t* outer = slot + k;        // half-edge across each link edge (or -1)
          std::int32_t* work = outer + k;        // the polygon being clipped / the stack
          std::int64_t d = 0;
          std::int32_t last = -1;
          const bool boundary =
              M.fan(b, [&](std::int32_t a, std::int32_t c, std::int32_t t, int kk) {
                link[d] = a, slot[d] = t, outer[d] = M.twin[3 * std::int64_t(t) + (kk + 1) % 3];
                last = c;
                ++d;
                return true;
              });
          const std::int64_t nl = boundary ? d + 1 : d;  // == k
          if (boundary) link[d] = last;
          near[b] = link[0];
          // The fan goes: the half-edges around it are open (re-paired below where a new
          // triangle has the edge; on the boundary a link edge may stay open).
          for (std::int64_t i = 0; i < d; ++i) {
            M.alive[slot[i]] = 0;
            if (outer[i] >= 0) M.twin[outer[i]] = -1;
          }
          std::int64_t used = 0;
          auto emit = [&](std::int32_t x, std::int32_t y, std::int32_t z) {
            const std::int32_t t = slot[used++];
            M.tri[3 * std::int64_t(t)] = x, M.tri[3 * std::int64_t(t) + 1] = y;
            M.tri[3 * std::int64_t(t) + 2] = z;
            M.alive[t] = 1;
          };
          auto at = [&](std::int32_t v) { return pos + 2 * std::int64_t(v); };
          if (!boundary) {
            // Ear clipping of the link (a simple counter-clockwise polygon).
            for (std::int64_t u = 0; u < nl; ++u) work[u] = link[u];
            const std::int64_t left = digital::clip_ears(
                work, nl,
                [&](std::int32_t x, std::int32_t y, std::int32_t z) {
                  return orient(at(x), at(y), at(z));
                },
                emit);
            if (left >= 3) atomic_add(&cnt[2], std::int64_t(1));  // (a hole: the check refuses)
            atomic_add(&cnt[0], std::int64_t(1));
          } else {
            // The chain the vertex leaves, from the start of its incoming boundary edge to the
            // end of its outgoing one, made convex (angularly monotone around the deleted
            // vertex: the monotone-chain hull, each popped vertex's triangle beneath it).
            std::int64_t top = 0;
            for (std::int64_t u = nl - 1; u >= 0; --u) {
              const std::int32_t v = link[u];
              while (top >= 2 && orient(at(work[top - 2]), at(work[top - 1]), at(v)) < 0) {
                emit(work[top - 2], v, work[top - 1]);
                --top;
              }
              work[top++] = v;
            }
            atomic_add(&cnt[1], std::int64_t(1));
          }
          // Pair the new half-edges: a link edge's with the half-edge that was across it, the
          // others with each other.
          for (std::int64_t u = 0; u < used; ++u)
            for (int kk = 0; kk < 3; ++kk) {
              const std::int32_t t = slot[u];
              const std::int64_t e = 3 * std::int64_t(t) + kk;
              const std::int32_t x = M.tri[e], y = M.at(t, kk + 1);
              std::int32_t tw = -1;
              for (std::int64_t i = 0; i < d && tw < 0; ++i)
                if (link[i] == x && link[(i + 1) % nl] == y) {
                  tw = outer[i];
                  if (tw >= 0) M.twin[tw] = std::int32_t(e);
                  if (tw < 0) tw = -2;  // (a link edge on the boundary: stays so)
                }
              for (std::int64_t v = 0; v < used && tw == -1; ++v)
                for (int k2 = 0; k2 < 3; ++k2) {
                  const std::int32_t t2 = slot[v];
                  if (M.at(t2, k2) == y && M.at(t2, k2 + 1) == x) tw = 3 * t2 + k2;
                }
              M.twin[e] = tw < 0 ? -1 : tw;
            }
          // The link's vertices keep a live triangle of theirs (or none: missing points).
          M.some[b] = -1;
          for (std::int64_t i = 0; i < nl; ++i) {
            const std::int32_t a = link[i];
            std::int32_t t = -1;
            for (std::int64_t u = 0; u < used && t < 0; ++u)
              if (M.at(slot[u], 0) == a || M.at(slot[u], 1) == a || M.at(slot[u], 2) == a)
                t = slot[u];
            if (t < 0 && i < d && outer[i] >= 0) t = outer[i] / 3;
            if (t < 0 && i > 0 && outer[i - 1] >= 0) t = outer[i - 1] / 3;
            if (t < 0 && i == 0 && !boundary && outer[d - 1] >= 0) t = outer[d - 1] / 3;
            M.some[a] = t;
          }
          // One left without a triangle walks, when inserted, from a link vertex that has one.
          for (std::int64_t i = 0; i < nl; ++i)
            if (M.some[link[i]] < 0)
              for (std::int64_t j = 1; j < nl; ++j)
                if (M.some[link[(i + j) % nl]] >= 0) {
                  near[link[i]] = link[(i + j) % nl];
                  break;
                }
          done[b] = r;
        });
    nbad = ex.copy_if(
        la, nbad, lb, GG_LAMBDA(std::int32_t v) { return done[v] == kPending; });
    std::swap(la, lb);
    if (++round > 100000) throw Error(ErrorCode::Internal, "shifting: the deletions do not end");
  }
  std::int64_t c[3];
  ex.to_host(cnt, 3, c);
  out.bad_inner = c[0], out.bad_boundary = c[1];
  out.delete_rounds = round;
  phase("shift_bad");
  // The start: live triangles renumbered, their twins, and the checks' inputs.
  auto d_slot = ex.template alloc<std::int32_t>(std::size_t(nt + 1));
  std::int32_t* slot = d_slot.data();
  ex.exclusive_scan_of(
      nt + 1, GG_LAMBDA(std::int64_t t)->std::int32_t { return t < nt ? M.alive[t] : 0; }, slot);
  std::int32_t live = 0;
  ex.to_host(slot + nt, 1, &live);
  auto o_tri = ex.template alloc<std::int32_t>(std::size_t(3 * live));
  auto o_twin = ex.template alloc<std::int32_t>(std::size_t(3 * live));
  std::int32_t* OT = o_tri.data();
  std::int32_t* OW = o_twin.data();
  auto d_flat = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      nt,
      GG_LAMBDA(std::int64_t t)->std::int64_t {
        if (!M.alive[t]) return 0;
        const std::int64_t s = slot[t];
        for (int k = 0; k < 3; ++k) {
          const std::int32_t o = M.twin[3 * t + k];
          OT[3 * s + k] = M.tri[3 * t + k];
          OW[3 * s + k] = o < 0 ? -1 : 3 * slot[o / 3] + o % 3;
        }
        return orient(pos + 2 * std::int64_t(M.tri[3 * t]),
                      pos + 2 * std::int64_t(M.tri[3 * t + 1]),
                      pos + 2 * std::int64_t(M.tri[3 * t + 2])) <= 0;
      },
      std::int64_t(0), thrust::plus<std::int64_t>(), d_flat.data());
  std::int64_t flat = 0;
  ex.to_host(d_flat.data(), 1, &flat);
  out.not_ccw = flat + c[2];
  // Hints: a missing point's pixel site, a deleted site's first neighbour, followed to a vertex
  // of the start; where that fails (a site no triangle had, a link vertex a deletion left
  // without triangles), the site of a pixel near its own that the start has.
  HeldStart S;
  S.hint = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* hint = S.hint.data();
  const std::int32_t* colour = H.colour.size() ? H.colour.data() : nullptr;
  const std::int64_t gh = sk.height;
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        if (M.some[i] >= 0) {
          hint[i] = -1;
          return;
        }
        std::int32_t v = near[i];
        for (int s = 0; s < 64 && v >= 0 && M.some[v] < 0; ++s) v = near[v] == v ? -1 : near[v];
        if (v >= 0 && M.some[v] >= 0) {
          hint[i] = v;
          return;
        }
        v = -1;
        const std::int64_t px = pixel[i] % w, py = pixel[i] / w;
        for (std::int64_t r = 1; r <= 8 && v < 0 && colour; ++r)
          for (std::int64_t dy = -r; dy <= r && v < 0; ++dy)
            for (std::int64_t dx = -r; dx <= r && v < 0; ++dx) {
              const std::int64_t qx = px + dx, qy = py + dy;
              if (qx < 0 || qy < 0 || qx >= w || qy >= gh) continue;
              const std::int32_t c = colour[qy * w + qx];
              if (c >= 0 && M.some[c] >= 0) v = c;
            }
        hint[i] = v;
      });
  std::int64_t counts[2] = {0, 0};
  {
    auto d_c = ex.template alloc<std::int64_t>(2);
    ex.transform_reduce_into(
        n, GG_LAMBDA(std::int64_t i)->std::int64_t { return M.some[i] >= 0; }, std::int64_t(0),
        thrust::plus<std::int64_t>(), d_c.data());
    ex.transform_reduce_into(
        n, GG_LAMBDA(std::int64_t i)->std::int64_t { return state[i] == kShifted; },
        std::int64_t(0), thrust::plus<std::int64_t>(), d_c.data() + 1);
    ex.to_host(d_c.data(), 2, counts);
  }
  out.vertices = counts[0], out.shifted = counts[1];
  S.tri = std::move(o_tri), S.twin = std::move(o_twin), S.nt = live;
  out.triangle_count = live;
  phase("shift_output");
  // The whole check, from the boundary at the points' own coordinates.
  out.reason = digital::check_start(rim_records(ex, OT, OW, live, {P, nullptr, 0}), out);
  out.valid = out.reason.empty();
  phase("shift_check");
  return S;
}
