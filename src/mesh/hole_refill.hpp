// The holes that removed vertices leave in a Delaunay triangulation, filled (internal;
// DynamicDelaunay2d and DynamicDelaunay3d::remove, issue 47).
//
// Removing points P_r from points P leaves P' = P \ P_r. A simplex of the old triangulation
// without a removed vertex keeps an empty circumsphere among P', so it stays; the others (the
// hole) go. What fills the hole is found from a small triangulation: D, the Delaunay
// triangulation of the hole's vertices that remain (and of the copies that take a removed
// vertex's place). Every new simplex of DT(P') lies in the hole and has an empty circumsphere
// among P' and so among those vertices: it is a simplex of D. D's simplices inside the hole tile
// it, and so do DT(P')'s, so they are the same simplices. (All under the perturbation, which
// depends on the points alone: D and DT(P') are triangulations of the same perturbed points.)
//
// Which of D's simplices are inside: each face between the hole and a simplex that stays is a
// face of D too, oriented: the D simplex that holds it with the hole's orientation (the opposite
// of the staying simplex's) is inside. From those seeds the inside is flooded across D's faces
// that are not such boundary faces. Matching uses a hash of the oriented face (its sorted
// vertices and the parity of its orientation), sorted, then compared exactly.
//
// Both stores are given plainly: K vertices per simplex (labels: input indices, the infinity
// vertex as any label the two share), neighbours as simplex indices (-1: none), dead simplices
// with v[0] == -1.
#pragma once
#include <cstdint>
#include <utility>

#include "base/hd.hpp"
#include "exec/atomics.hpp"
#include <thrust/functional.h>

namespace gpugeom::mesh {

namespace refill_detail {

// Face k of simplex v (K vertices): its K - 1 vertices sorted into f, and the parity of its
// induced orientation ((-1)^k times the sign of the sorting permutation). Two positively
// oriented simplices that share a face give it opposite parities.
template <int K>
GG_HD int oriented_face(const std::int32_t* v, int k, std::int32_t* f) {
  int c = 0;
  for (int j = 0; j < K; ++j)
    if (j != k) f[c++] = v[j];
  int parity = k & 1;
  for (int i = 1; i < K - 1; ++i)
    for (int j = i; j > 0 && f[j - 1] > f[j]; --j) {
      const std::int32_t t = f[j];
      f[j] = f[j - 1];
      f[j - 1] = t;
      parity ^= 1;
    }
  return parity;
}

GG_HD inline std::uint64_t mix(std::uint64_t h) {
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  return h ^ (h >> 31);
}

template <int K>
GG_HD std::uint64_t face_key(const std::int32_t* v, int k) {
  std::int32_t f[K - 1];
  std::uint64_t h = std::uint64_t(oriented_face<K>(v, k, f)) + 0x9e3779b97f4a7c15ull;
  for (int i = 0; i < K - 1; ++i) h = mix(h ^ std::uint32_t(f[i]));
  return h;
}

template <int K>
GG_HD bool same_face(const std::int32_t* a, int ka, const std::int32_t* b, int kb) {
  std::int32_t fa[K - 1], fb[K - 1];
  if (oriented_face<K>(a, ka, fa) != oriented_face<K>(b, kb, fb)) return false;
  for (int i = 0; i < K - 1; ++i)
    if (fa[i] != fb[i]) return false;
  return true;
}

}  // namespace refill_detail

// Per point: 1 where removed by this call (gone now, and not in the earlier flags was, or null).
template <class Exec>
typename Exec::template Buffer<std::int8_t> removed_now(Exec& ex, const std::int8_t* gone,
                                                        const std::int8_t* was, std::int64_t n) {
  auto out = ex.template alloc<std::int8_t>(std::size_t(n));
  std::int8_t* o = out.data();
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) { o[i] = gone[i] && !(was && was[i]); });
  return out;
}

// Per simplex of a plain store: 1 where a vertex is removed now (the hole). Returns how many.
// [synchronises]
template <int K, class Exec>
std::int64_t hole_flags(Exec& ex, const std::int32_t* v, std::int64_t count, const std::int8_t* now,
                        std::int8_t* hole) {
  ex.for_each_index(
      count, GG_LAMBDA(std::int64_t t) {
        bool h = false;
        if (v[K * t] != -1)
          for (int k = 0; k < K; ++k) h = h || (v[K * t + k] >= 0 && now[v[K * t + k]]);
        hole[t] = h;
      });
  auto cnt = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      count, GG_LAMBDA(std::int64_t t)->std::int64_t { return hole[t]; }, std::int64_t(0),
      thrust::plus<std::int64_t>(), cnt.data());
  std::int64_t c = 0;
  ex.to_host(cnt.data(), 1, &c);
  return c;
}

// The points D triangulates, into ids (input indices, increasing): the hole's vertices that
// stay, and each removed vertex's copy that takes its place (a vertex now: new_dup -1; its
// copy's before: old_dup). Returns how many. [synchronises]
template <int K, class Exec>
std::int64_t hole_vertices(Exec& ex, const std::int32_t* v, std::int64_t count,
                           const std::int8_t* hole, const std::int8_t* now,
                           const std::int32_t* old_dup, const std::int32_t* new_dup, std::int64_t n,
                           std::int32_t* ids) {
  auto d_mark = ex.template alloc<std::int8_t>(std::size_t(n));
  std::int8_t* mark = d_mark.data();
  ex.fill(mark, n, std::int8_t(0));
  ex.for_each_index(
      count, GG_LAMBDA(std::int64_t t) {
        if (!hole[t]) return;
        for (int k = 0; k < K; ++k) {
          const std::int32_t w = v[K * t + k];
          if (w >= 0 && !now[w]) mark[w] = 1;
        }
      });
  if (old_dup)
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          const std::int32_t d = old_dup[i];
          if (d >= 0 && now[d] && new_dup && new_dup[i] == -1) mark[i] = 1;
        });
  return ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return mark[i] != 0; }, ids);
}

// The filled triangulation: the old simplices that stay (in their order), then D's inside ones
// (in D's order), compact, with neighbours; touched: 1 for the new simplices and the staying
// ones next to them. ok false where the pieces do not fit (a boundary face D lacks where
// every face must have a neighbour, or a flood that leaves through a face of D's hull).
template <class Exec>
struct Refilled {
  typename Exec::template Buffer<std::int32_t> v, n;
  typename Exec::template Buffer<std::int8_t> touched;
  std::int64_t count = 0, inside = 0, boundary = 0, unmatched = 0;
  bool ok = false;
};

// old: ov, on (ont simplices), hole (per old simplex: 1 where it goes). d: dv, dn (dnt).
// closed: every face has a neighbour (3D with its infinite simplices): then each boundary face
// must be in D; else (2D, finite triangles only) one D lacks is a new hull edge. mark (or null):
// per point, set to 1 at the vertices of the staying simplex across each boundary face D lacks
// (a move's refill at the new places grows its hole there). [synchronises]
template <int K, class Exec>
Refilled<Exec> refill_holes(Exec& ex, const std::int32_t* ov, const std::int32_t* on,
                            std::int64_t ont, const std::int8_t* hole, const std::int32_t* dv,
                            const std::int32_t* dn, std::int64_t dnt, bool closed,
                            std::int8_t* mark = nullptr) {
  using refill_detail::face_key;
  using refill_detail::same_face;
  Refilled<Exec> R;
  // the hole's faces onto staying simplices: entries r * K + k
  auto d_h = ex.template alloc<std::int32_t>(std::size_t(ont));
  std::int32_t* H = d_h.data();
  const std::int64_t nh = ex.compact_indices(
      ont, GG_LAMBDA(std::int64_t t) { return hole[t] != 0; }, H);
  auto d_bi = ex.template alloc<std::int32_t>(std::size_t(K * nh));
  std::int32_t* bi = d_bi.data();
  const std::int64_t nb = ex.compact_indices(
      K * nh,
      GG_LAMBDA(std::int64_t e) {
        const std::int32_t t = on[K * std::int64_t(H[e / K]) + e % K];
        return t >= 0 && !hole[t];
      },
      bi);
  R.boundary = nb;
  // keys: the nb boundary records, then every face of D (dead ones never match)
  const std::int64_t nk = nb + K * dnt;
  auto d_key = ex.template alloc<std::uint64_t>(std::size_t(nk));
  auto d_id = ex.template alloc<std::int32_t>(std::size_t(nk));
  std::uint64_t* key = d_key.data();
  std::int32_t* id = d_id.data();
  ex.for_each_index(
      nk, GG_LAMBDA(std::int64_t i) {
        if (i < nb) {
          const std::int32_t e = bi[i];
          key[i] = face_key<K>(ov + K * std::int64_t(H[e / K]), e % K);
        } else {
          const std::int64_t e = i - nb;
          key[i] = face_key<K>(dv + K * (e / K), int(e % K));
        }
        id[i] = std::int32_t(i);
      });
  ex.sort_by_key(key, id, nk);
  // each boundary record's D face (entry d * K + k), -1 if none; each D face's record, -1
  auto d_match = ex.template alloc<std::int32_t>(std::size_t(nb));
  auto d_dbound = ex.template alloc<std::int32_t>(std::size_t(K * dnt));
  auto d_inside = ex.template alloc<std::int32_t>(std::size_t(dnt));
  auto d_list = ex.template alloc<std::int32_t>(std::size_t(2 * dnt + 2));
  auto d_cnt = ex.template alloc<std::int64_t>(3);  // unmatched, next list length, escapes
  std::int32_t* match = d_match.data();
  std::int32_t* dbound = d_dbound.data();
  std::int32_t* inside = d_inside.data();
  std::int64_t* cnt = d_cnt.data();
  ex.fill(match, nb, std::int32_t(-1));
  ex.fill(dbound, K * dnt, std::int32_t(-1));
  ex.fill(inside, dnt, std::int32_t(0));
  ex.fill(cnt, 3, std::int64_t(0));
  ex.for_each_index(
      nk, GG_LAMBDA(std::int64_t p) {
        const std::int32_t i = id[p];
        if (i >= nb) return;
        const std::int32_t e = bi[i];
        const std::int32_t* r = ov + K * std::int64_t(H[e / K]);
        std::int32_t found = -1;
        for (int dir = -1; dir <= 1 && found < 0; dir += 2)
          for (std::int64_t q = p + dir; q >= 0 && q < nk && key[q] == key[p] && found < 0;
               q += dir) {
            const std::int32_t j = id[q];
            if (j < nb) continue;
            const std::int64_t f = j - nb;
            const std::int32_t* d = dv + K * (f / K);
            if (d[0] != -1 && same_face<K>(r, e % K, d, int(f % K))) found = std::int32_t(f);
          }
        match[i] = found;
        if (found < 0) {
          atomic_add(&cnt[0], std::int64_t(1));
          if (mark) {
            const std::int32_t t = on[K * std::int64_t(H[e / K]) + e % K];
            for (int k = 0; k < K; ++k)
              if (ov[K * std::int64_t(t) + k] >= 0) mark[ov[K * std::int64_t(t) + k]] = 1;
          }
          return;
        }
        dbound[found] = i;
      });
  // the flood: seeds, then rounds across faces that are not boundary faces
  std::int32_t* list = d_list.data();
  std::int32_t* cur = list;
  std::int32_t* next = list + dnt + 1;
  ex.for_each_index(
      nb, GG_LAMBDA(std::int64_t i) {
        const std::int32_t f = match[i];
        if (f < 0) return;
        const std::int32_t d = f / K;
        if (atomic_exchange(&inside[d], std::int32_t(1)) == 0) cur[append_slot(&cnt[1])] = d;
      });
  if (nb == 0)  // the hole is all of it (no simplex stays): all of D fills it
    ex.for_each_index(
        dnt, GG_LAMBDA(std::int64_t d) {
          if (dv[K * d] != -1) inside[d] = 1, cur[append_slot(&cnt[1])] = std::int32_t(d);
        });
  std::int64_t h[3];
  ex.to_host(cnt, 3, h);
  R.unmatched = h[0];
  std::int64_t len = nb == 0 ? 0 : h[1], total = h[1];
  while (len > 0) {
    ex.fill(cnt + 1, 1, std::int64_t(0));
    const std::int32_t* c = cur;
    std::int32_t* x = next;
    ex.for_each_index(
        len, GG_LAMBDA(std::int64_t i) {
          const std::int32_t d = c[i];
          for (int k = 0; k < K; ++k) {
            if (dbound[K * std::int64_t(d) + k] >= 0) continue;
            const std::int32_t o = dn[K * std::int64_t(d) + k];
            if (o < 0) continue;  // a hull edge of D (2D): a hull edge of the new triangulation
            if (atomic_exchange(&inside[o], std::int32_t(1)) == 0) x[append_slot(&cnt[1])] = o;
          }
        });
    ex.to_host(cnt + 1, 1, &len);
    total += len;
    std::swap(cur, next);
  }
  R.inside = total;
  if (closed && R.unmatched) return R;  // (ok false: the caller builds afresh)
  // new numbering: staying simplices, then D's inside ones
  auto d_rank = ex.template alloc<std::int64_t>(std::size_t(ont + 1));
  auto d_drank = ex.template alloc<std::int64_t>(std::size_t(dnt + 1));
  std::int64_t* rank = d_rank.data();
  std::int64_t* drank = d_drank.data();
  ex.exclusive_scan_of(
      ont + 1,
      GG_LAMBDA(std::int64_t t)->std::int64_t { return t < ont && !hole[t] && ov[K * t] != -1; },
      rank);
  ex.exclusive_scan_of(
      dnt + 1, GG_LAMBDA(std::int64_t d)->std::int64_t { return d < dnt && inside[d] != 0; },
      drank);
  std::int64_t nkept = 0, nin = 0;
  ex.to_host(rank + ont, 1, &nkept);
  ex.to_host(drank + dnt, 1, &nin);
  R.count = nkept + nin;
  R.v = ex.template alloc<std::int32_t>(std::size_t(K * R.count));
  R.n = ex.template alloc<std::int32_t>(std::size_t(K * R.count));
  R.touched = ex.template alloc<std::int8_t>(std::size_t(R.count));
  std::int32_t* nv = R.v.data();
  std::int32_t* nn = R.n.data();
  std::int8_t* touched = R.touched.data();
  ex.fill(touched, R.count, std::int8_t(0));
  ex.fill(cnt + 2, 1, std::int64_t(0));
  ex.for_each_index(
      ont, GG_LAMBDA(std::int64_t t) {
        if (hole[t] || ov[K * t] == -1) return;
        const std::int64_t s = rank[t];
        for (int k = 0; k < K; ++k) {
          const std::int32_t o = on[K * t + k];
          nv[K * s + k] = ov[K * t + k];
          nn[K * s + k] = o < 0 || hole[o] ? -1 : std::int32_t(rank[o]);  // (hole: below)
        }
      });
  ex.for_each_index(
      dnt, GG_LAMBDA(std::int64_t d) {
        if (!inside[d]) return;
        const std::int64_t s = nkept + drank[d];
        touched[s] = 1;
        for (int k = 0; k < K; ++k) {
          nv[K * s + k] = dv[K * d + k];
          const std::int32_t o = dn[K * d + k];
          std::int32_t w = -1;
          if (dbound[K * d + k] < 0 && o >= 0) {
            if (inside[o])
              w = std::int32_t(nkept + drank[o]);
            else
              atomic_add(&cnt[2], std::int64_t(1));  // the flood met an outside simplex
          }
          nn[K * s + k] = w;  // (boundary faces: below)
        }
      });
  // the boundary faces joined: the staying simplex t across from hole simplex r
  ex.for_each_index(
      nb, GG_LAMBDA(std::int64_t i) {
        const std::int32_t e = bi[i];
        const std::int32_t r = H[e / K];
        const std::int32_t t = on[K * std::int64_t(r) + e % K];
        const std::int64_t s = rank[t];
        int kt = -1;
        for (int j = 0; j < K; ++j)
          if (on[K * std::int64_t(t) + j] == r) kt = j;
        touched[s] = 1;
        const std::int32_t f = match[i];
        if (f < 0 || kt < 0) {
          if (kt < 0) atomic_add(&cnt[2], std::int64_t(1));
          return;  // (2D: the edge is on the hull now)
        }
        const std::int64_t d = f / K, sd = nkept + drank[d];
        nn[K * s + kt] = std::int32_t(sd);
        nn[K * sd + f % K] = std::int32_t(s);
      });
  ex.to_host(cnt + 2, 1, &h[2]);
  R.ok = h[2] == 0;
  return R;
}

}  // namespace gpugeom::mesh
