// What a distributed-Delaunay block requires of its triangulation, the output of its owned
// simplices and their neighbours across blocks, matched by their faces
// (include/gpugeom/blocks.hpp): the rules of gpugeom.dask (python/gpugeom/dask/ _ghost.py), for its
// CPU and GPU blocks alike, one simplex at a time. NumPy's gathers over every simplex cost a second
// for a block of 2·10^6 points.
#include <algorithm>
#if __has_include(<parallel/algorithm>)
#include <parallel/algorithm>
#endif
#include <limits>
#include <string>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "gpugeom/common.hpp"
#include "blocks/pass.hpp"
#include "blocks/simplex_rules.hpp"

namespace gpugeom {

namespace {

using blocks_detail::lowest_at;

// The passes on simplices and neighbours of either index width (a GPU block's come to the
// host as the triangulation gives them, int32: half the bytes of int64).
template <class I>
BlockRequired required_of(const I* simplices, std::int64_t m, int dim, const std::uint8_t* owned,
                          int threads) {
  blocks_detail::check_dim(dim, "block_required");
  const int d1 = dim + 1;
  blocks_detail::ThreadScope scope(threads);
  BlockRequired out;
  out.required.resize(std::size_t(m));
  HostVector<std::uint8_t> mine(static_cast<std::size_t>(m));
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < m; ++i) {
    const I* v = simplices + i * d1;
    std::uint8_t any = 0;
    for (int k = 0; k < d1; ++k) any |= owned[v[k]] ? 1 : 0;
    out.required[std::size_t(i)] = any;
    mine[std::size_t(i)] = owned[v[lowest_at(v, d1)]] ? 1 : 0;
  }
  // the owned rows in order
  blocks_detail::ordered_compact(
      m, [&](std::int64_t i) { return mine[std::size_t(i)] != 0; },
      [&](std::int64_t total) { out.owned_rows.resize(std::size_t(total)); },
      [&](std::int64_t i, std::int64_t r) { out.owned_rows[std::size_t(r)] = i; });
  return out;
}

template <class I>
BlockOutput output_of(const I* simplices, const I* neighbors, std::int64_t m, int dim,
                      const std::int64_t* rows, std::int64_t count, const std::int32_t* ids,
                      const std::int32_t* blk, const double* points, std::int64_t n, int threads) {
  blocks_detail::check_dim(dim, "block_output");
  const int d1 = dim + 1;
  constexpr std::int64_t most = std::numeric_limits<std::int32_t>::max();
  if (count * d1 > most || n > most)
    throw Error(ErrorCode::Unsupported,
                "block_output: a block of " + std::to_string(count) + " owned simplices over " +
                    std::to_string(n) +
                    " local points is too large for 32-bit positions: use more blocks");
  blocks_detail::ThreadScope scope(threads);
  BlockOutput out;
  // (each simplex's row, in the simplices' own index width: at 10^7 points half the fresh pages)
  HostVector<I> pos(static_cast<std::size_t>(m));
  const std::size_t cells = std::size_t(count) * std::size_t(d1);
  out.simplices.resize(cells);
  out.neighbors.resize(cells);
  HostVector<std::uint8_t> used(static_cast<std::size_t>(n));
  // (the fills in parallel too: a GPU block's arrays are hundreds of MB)
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < m; ++i) pos[std::size_t(i)] = -1;
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < std::int64_t(used.size()); ++i) used[std::size_t(i)] = 0;
#pragma omp parallel for schedule(static)
  for (std::int64_t r = 0; r < count; ++r) pos[std::size_t(rows[r])] = I(r);
  std::int64_t requests = 0;
#pragma omp parallel for schedule(static) reduction(+ : requests)
  for (std::int64_t r = 0; r < count; ++r) {
    const I* v = simplices + rows[r] * d1;
    const I* nb = neighbors + rows[r] * d1;
    for (int k = 0; k < d1; ++k) {
      out.simplices[std::size_t(r * d1 + k)] = ids[v[k]];
      const std::int64_t t = nb[k];
      // (the owners are looked up for hull faces only: random reads over every simplex cost
      // more than the rest of the pass)
      const std::int64_t c = blocks_detail::face_code(
          v, d1, k, t, t < 0 ? -1 : std::int64_t(pos[std::size_t(t)]), [&](I u) { return blk[u]; });
      out.neighbors[std::size_t(r * d1 + k)] = std::int32_t(c);
      requests += c < -1;
    }
  }
  out.request_owner.resize(std::size_t(requests));
  out.request_pos.resize(std::size_t(requests));
  out.request_key.resize(std::size_t(requests) * std::size_t(dim));
  out.request_open.resize(std::size_t(requests));
  // the vertices the rows use (shared between rows: the same byte written by two threads, so
  // atomically), then in order: the requests (row-major), the vertices
  std::uint8_t* mark = used.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t r = 0; r < count; ++r) {
    const I* v = simplices + rows[r] * d1;
    for (int k = 0; k < d1; ++k) {
#pragma omp atomic write
      mark[v[k]] = std::uint8_t(1);
    }
  }
  std::int32_t* nbl = out.neighbors.data();
  blocks_detail::ordered_compact(
      std::int64_t(cells), [&](std::int64_t c) { return nbl[c] < -1; }, [&](std::int64_t) {},
      [&](std::int64_t c, std::int64_t q) {
        out.request_open[std::size_t(q)] = nbl[c] == -3 ? 1 : 0;
        const I* v = simplices + rows[c / d1] * d1;
        const I low = blocks_detail::request_key(
            v, d1, int(c % d1), [&](I u) { return ids[u]; }, out.request_key.data() + q * dim);
        out.request_owner[std::size_t(q)] = blk[low];
        out.request_pos[std::size_t(q)] = std::int32_t(c);
      });
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < std::int64_t(cells); ++c)
    if (nbl[c] == -3) nbl[c] = -2;
  blocks_detail::ordered_compact(
      n, [&](std::int64_t i) { return mark[i] != 0; },
      [&](std::int64_t total) { out.vertices.resize(std::size_t(total)); },
      [&](std::int64_t i, std::int64_t k) { out.vertices[std::size_t(k)] = std::int32_t(i); });
  // the vertices' ids and coordinates: gathers over the block, so in parallel too
  const std::int64_t nv = std::int64_t(out.vertices.size());
  out.vertex_ids.resize(std::size_t(nv));
  if (points) out.vertex_points.resize(std::size_t(nv) * std::size_t(dim));
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < nv; ++k) {
    const std::int64_t v = out.vertices[std::size_t(k)];
    out.vertex_ids[std::size_t(k)] = ids[v];
    if (points)
      for (int j = 0; j < dim; ++j)
        out.vertex_points[std::size_t(k * dim + j)] = points[v * dim + j];
  }
  return out;
}

}  // namespace

BlockRequired block_required(const std::int64_t* simplices, const std::int64_t* neighbors,
                             std::int64_t m, int dim, const std::uint8_t* owned, int threads) {
  (void)neighbors;  // (the interface keeps them: the rule may come to need them again)
  return required_of(simplices, m, dim, owned, threads);
}
BlockRequired block_required(const std::int32_t* simplices, const std::int32_t* neighbors,
                             std::int64_t m, int dim, const std::uint8_t* owned, int threads) {
  (void)neighbors;  // (the interface keeps them: the rule may come to need them again)
  return required_of(simplices, m, dim, owned, threads);
}
BlockOutput block_output(const std::int64_t* simplices, const std::int64_t* neighbors,
                         std::int64_t m, int dim, const std::int64_t* rows, std::int64_t count,
                         const std::int32_t* ids, const std::int32_t* blk, const double* points,
                         std::int64_t n, int threads) {
  return output_of(simplices, neighbors, m, dim, rows, count, ids, blk, points, n, threads);
}
BlockOutput block_output(const std::int32_t* simplices, const std::int32_t* neighbors,
                         std::int64_t m, int dim, const std::int64_t* rows, std::int64_t count,
                         const std::int32_t* ids, const std::int32_t* blk, const double* points,
                         std::int64_t n, int threads) {
  return output_of(simplices, neighbors, m, dim, rows, count, ids, blk, points, n, threads);
}

namespace {

template <class K>
HostVector<std::int64_t> match_of(const K* keys, const std::int64_t* positions,
                                  const std::uint8_t* open, std::int64_t q, int dim, int threads) {
  blocks_detail::check_dim(dim, "match_faces");
  blocks_detail::ThreadScope scope(threads);
  // the requests in the order of their keys (then positions: the order does not depend on
  // where they came from), so that the two of a face are next to each other
  std::vector<std::int64_t> idx(static_cast<std::size_t>(std::max<std::int64_t>(q, 0)));
  for (std::int64_t r = 0; r < q; ++r) idx[std::size_t(r)] = r;
  // (a strict order: the result does not depend on the sort, so the threads may share it; the
  // several-device path matches 10^5-10^6 faces per block at 10^7 points)
  const auto before = [&](std::int64_t x, std::int64_t y) {
    const K *a = keys + x * dim, *b = keys + y * dim;
    for (int k = 0; k < dim; ++k)
      if (a[k] != b[k]) return a[k] < b[k];
    return positions[x] < positions[y];
  };
#if __has_include(<parallel/algorithm>)
  __gnu_parallel::sort(idx.begin(), idx.end(), before);
#else
  std::sort(idx.begin(), idx.end(), before);
#endif
  auto same = [&](std::int64_t x, std::int64_t y) {
    return std::equal(keys + x * dim, keys + (x + 1) * dim, keys + y * dim);
  };
  HostVector<std::int64_t> out(static_cast<std::size_t>(std::max<std::int64_t>(q, 0)));
  for (std::int64_t k = 0; k < q;) {
    const std::int64_t x = idx[std::size_t(k)];
    std::int64_t run = 1;
    while (k + run < q && same(x, idx[std::size_t(k + run)])) ++run;
    if (run == 1 && open && open[x]) {  // a face on the hull
      out[std::size_t(x)] = -1;
      k += 1;
      continue;
    }
    if (run != 2)
      throw Error(ErrorCode::Internal,
                  "match_faces: the face of request " + std::to_string(x) + " (position " +
                      std::to_string(positions[x]) + ") comes " + std::to_string(run) +
                      " times, not twice (a bug: please report it with the input)");
    const std::int64_t y = idx[std::size_t(k + 1)];
    out[std::size_t(x)] = positions[y];
    out[std::size_t(y)] = positions[x];
    k += 2;
  }
  return out;
}

}  // namespace

HostVector<std::int64_t> match_faces(const std::int64_t* keys, const std::int64_t* positions,
                                     const std::uint8_t* open, std::int64_t q, int dim,
                                     int threads) {
  return match_of(keys, positions, open, q, dim, threads);
}
HostVector<std::int64_t> match_faces(const std::int32_t* keys, const std::int64_t* positions,
                                     const std::uint8_t* open, std::int64_t q, int dim,
                                     int threads) {
  return match_of(keys, positions, open, q, dim, threads);
}

template <class Index>
HostVector<Index> block_neighbors(const std::int32_t* neighbors, std::int64_t m, int dim,
                                  std::int64_t offset, const std::int64_t* pos,
                                  const std::int64_t* across, std::int64_t q, int threads) {
  blocks_detail::check_dim(dim, "block_neighbors");
  const int d1 = dim + 1;
  constexpr std::int64_t most = std::numeric_limits<Index>::max();
  if (offset < 0 || offset + m - 1 > most)
    throw Error(ErrorCode::InvalidArgument,
                "block_neighbors: the global simplices " + std::to_string(offset) + " to " +
                    std::to_string(offset + m - 1) + " pass the output's " +
                    std::to_string(8 * sizeof(Index)) + "-bit indices");
  blocks_detail::ThreadScope scope(threads);
  HostVector<Index> out(std::size_t(m) * std::size_t(d1));
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < m * d1; ++c) {
    const std::int64_t t = neighbors[c];
    out[std::size_t(c)] = Index(t >= 0 ? t + offset : (t == -1 ? -1 : -2));
  }
  for (std::int64_t r = 0; r < q; ++r) {
    if (pos[r] < 0 || pos[r] >= m * d1 || neighbors[pos[r]] != -2)
      throw Error(ErrorCode::InvalidArgument, "block_neighbors: answer " + std::to_string(r) +
                                                  " is for position " + std::to_string(pos[r]) +
                                                  ", not a face of another block's neighbour");
    if (across[r] > most)
      throw Error(ErrorCode::InvalidArgument,
                  "block_neighbors: answer " + std::to_string(r) + " names simplex " +
                      std::to_string(across[r]) + ", past the output's " +
                      std::to_string(8 * sizeof(Index)) + "-bit indices");
    out[std::size_t(pos[r])] = Index(across[r] < 0 ? -1 : across[r]);
  }
  std::int64_t missing = -1;
#pragma omp parallel for schedule(static) reduction(max : missing)
  for (std::int64_t c = 0; c < m * d1; ++c)
    if (out[std::size_t(c)] == -2) missing = std::max(missing, c);
  if (missing >= 0)
    throw Error(ErrorCode::Internal, "block_neighbors: the face at position " +
                                         std::to_string(missing) +
                                         " has no answer (a bug: please report it with the input)");
  return out;
}

template HostVector<std::int32_t> block_neighbors<std::int32_t>(const std::int32_t*, std::int64_t,
                                                                int, std::int64_t,
                                                                const std::int64_t*,
                                                                const std::int64_t*, std::int64_t,
                                                                int);
template HostVector<std::int64_t> block_neighbors<std::int64_t>(const std::int32_t*, std::int64_t,
                                                                int, std::int64_t,
                                                                const std::int64_t*,
                                                                const std::int64_t*, std::int64_t,
                                                                int);

}  // namespace gpugeom
