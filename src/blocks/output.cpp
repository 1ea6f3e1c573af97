// What a distributed-Delaunay block requires of its triangulation and the output of its owned
// simplices (include/gpugeom/blocks.hpp): the rules of gpugeom.dask (python/gpugeom/dask/
// _ghost.py), for its CPU and GPU blocks alike, one simplex at a time. NumPy's gathers over every
// simplex cost a second for a block of 2·10^6 points.
#include <algorithm>
#include <string>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "gpugeom/common.hpp"
#include "blocks/pass.hpp"

namespace gpugeom {

namespace {

// The lowest vertex's place (0..dim) in a simplex.
template <class I>
inline int lowest_at(const I* v, int d1) {
  int at = 0;
  for (int k = 1; k < d1; ++k)
    if (v[k] < v[at]) at = k;
  return at;
}

// The passes on simplices and neighbours of either index width (a GPU block's come to the
// host as the triangulation gives them, int32: half the bytes of int64).
template <class I>
BlockRequired required_of(const I* simplices, const I* neighbors, std::int64_t m, int dim,
                          const std::uint8_t* owned, int threads) {
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
  // the owned rows in order, then the rings (two owned simplices may share one: the same byte
  // written by two threads, so atomically)
  blocks_detail::ordered_compact(
      m, [&](std::int64_t i) { return mine[std::size_t(i)] != 0; },
      [&](std::int64_t total) { out.owned_rows.resize(std::size_t(total)); },
      [&](std::int64_t i, std::int64_t r) { out.owned_rows[std::size_t(r)] = i; });
  const std::int64_t count = std::int64_t(out.owned_rows.size());
  std::uint8_t* required = out.required.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t r = 0; r < count; ++r) {
    const std::int64_t i = out.owned_rows[std::size_t(r)];
    const std::int64_t t = neighbors[i * d1 + lowest_at(simplices + i * d1, d1)];
    if (t >= 0) {
#pragma omp atomic write
      required[t] = std::uint8_t(1);
    }
  }
  return out;
}

template <class I>
BlockOutput output_of(const I* simplices, const I* neighbors, std::int64_t m, int dim,
                      const std::int64_t* rows, std::int64_t count, const std::int64_t* ids,
                      const std::int64_t* blk, const double* points, std::int64_t n, int threads) {
  blocks_detail::check_dim(dim, "block_output");
  const int d1 = dim + 1;
  blocks_detail::ThreadScope scope(threads);
  BlockOutput out;
  HostVector<std::int64_t> pos(static_cast<std::size_t>(m));
  const std::size_t cells = std::size_t(count) * std::size_t(d1);
  out.simplices.resize(cells);
  out.neighbors.resize(cells);
  HostVector<std::uint8_t> used(static_cast<std::size_t>(n));
  // (the fills in parallel too: a GPU block's arrays are hundreds of MB)
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < m; ++i) pos[std::size_t(i)] = -1;
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) used[std::size_t(i)] = 0;
#pragma omp parallel for schedule(static)
  for (std::int64_t r = 0; r < count; ++r) pos[std::size_t(rows[r])] = r;
  std::int64_t requests = 0;
#pragma omp parallel for schedule(static) reduction(+ : requests)
  for (std::int64_t r = 0; r < count; ++r) {
    const I* v = simplices + rows[r] * d1;
    const I* nb = neighbors + rows[r] * d1;
    for (int k = 0; k < d1; ++k) {
      out.simplices[std::size_t(r * d1 + k)] = ids[v[k]];
      const std::int64_t t = nb[k];
      const std::int64_t p = t < 0 ? -1 : pos[std::size_t(t)];
      out.neighbors[std::size_t(r * d1 + k)] = t < 0 ? -1 : (p >= 0 ? p : -2);
      requests += t >= 0 && p < 0;
    }
  }
  out.request_owner.resize(std::size_t(requests));
  out.request_pos.resize(std::size_t(requests));
  out.request_key.resize(std::size_t(requests) * std::size_t(d1));
  // the vertices the rows use (shared between rows: the same byte written by two threads, so
  // atomically), then in order: the requests (row-major), the border rows, the vertices
  std::uint8_t* mark = used.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t r = 0; r < count; ++r) {
    const I* v = simplices + rows[r] * d1;
    for (int k = 0; k < d1; ++k) {
#pragma omp atomic write
      mark[v[k]] = std::uint8_t(1);
    }
  }
  const std::int64_t* nbl = out.neighbors.data();
  blocks_detail::ordered_compact(
      std::int64_t(cells), [&](std::int64_t c) { return nbl[c] == -2; }, [&](std::int64_t) {},
      [&](std::int64_t c, std::int64_t q) {
        const std::int64_t r = c / d1;
        const I* w = simplices + std::int64_t(neighbors[rows[r] * d1 + c % d1]) * d1;
        out.request_owner[std::size_t(q)] = blk[w[lowest_at(w, d1)]];
        out.request_pos[std::size_t(q)] = c;
        std::int64_t* key = out.request_key.data() + q * d1;
        for (int j = 0; j < d1; ++j) key[j] = ids[w[j]];
        std::sort(key, key + d1);
      });
  auto asked = [&](std::int64_t r) {
    for (int k = 0; k < d1; ++k)
      if (nbl[r * d1 + k] == -2) return true;
    return false;
  };
  blocks_detail::ordered_compact(
      count, asked,
      [&](std::int64_t total) {
        out.border_rows.resize(std::size_t(total));
        out.border_keys.resize(std::size_t(total) * std::size_t(d1));
      },
      [&](std::int64_t r, std::int64_t b) {
        out.border_rows[std::size_t(b)] = r;
        std::int64_t* key = out.border_keys.data() + b * d1;
        for (int k = 0; k < d1; ++k) key[k] = out.simplices[std::size_t(r * d1 + k)];
        std::sort(key, key + d1);
      });
  blocks_detail::ordered_compact(
      n, [&](std::int64_t i) { return mark[i] != 0; },
      [&](std::int64_t total) { out.vertices.resize(std::size_t(total)); },
      [&](std::int64_t i, std::int64_t k) { out.vertices[std::size_t(k)] = i; });
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
  return required_of(simplices, neighbors, m, dim, owned, threads);
}
BlockRequired block_required(const std::int32_t* simplices, const std::int32_t* neighbors,
                             std::int64_t m, int dim, const std::uint8_t* owned, int threads) {
  return required_of(simplices, neighbors, m, dim, owned, threads);
}
BlockOutput block_output(const std::int64_t* simplices, const std::int64_t* neighbors,
                         std::int64_t m, int dim, const std::int64_t* rows, std::int64_t count,
                         const std::int64_t* ids, const std::int64_t* blk, const double* points,
                         std::int64_t n, int threads) {
  return output_of(simplices, neighbors, m, dim, rows, count, ids, blk, points, n, threads);
}
BlockOutput block_output(const std::int32_t* simplices, const std::int32_t* neighbors,
                         std::int64_t m, int dim, const std::int64_t* rows, std::int64_t count,
                         const std::int64_t* ids, const std::int64_t* blk, const double* points,
                         std::int64_t n, int threads) {
  return output_of(simplices, neighbors, m, dim, rows, count, ids, blk, points, n, threads);
}

HostVector<std::int64_t> block_neighbors(const std::int64_t* neighbors, std::int64_t m, int dim,
                                         std::int64_t offset, const std::int64_t* request_owner,
                                         const std::int64_t* request_key,
                                         const std::int64_t* request_pos, std::int64_t q,
                                         const BlockBorder* borders, std::int64_t nborders,
                                         int threads) {
  blocks_detail::check_dim(dim, "block_neighbors");
  const int d1 = dim + 1;
  blocks_detail::ThreadScope scope(threads);
  HostVector<std::int64_t> out(std::size_t(m) * std::size_t(d1));
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < m * d1; ++c) {
    const std::int64_t t = neighbors[c];
    out[std::size_t(c)] = t >= 0 ? t + offset : -1;
  }
  // each border's rows in the order of their keys, then a binary search per request
  auto less = [d1](const std::int64_t* a, const std::int64_t* b) {
    return std::lexicographical_compare(a, a + d1, b, b + d1);
  };
  std::vector<std::vector<std::int64_t>> sorted(static_cast<std::size_t>(nborders));
#pragma omp parallel for schedule(dynamic)
  for (std::int64_t i = 0; i < nborders; ++i) {
    const BlockBorder& b = borders[i];
    auto& idx = sorted[std::size_t(i)];
    idx.resize(std::size_t(b.count));
    for (std::int64_t r = 0; r < b.count; ++r) idx[std::size_t(r)] = r;
    std::sort(idx.begin(), idx.end(), [&](std::int64_t x, std::int64_t y) {
      return less(b.keys + x * d1, b.keys + y * d1);
    });
  }
  std::int64_t missing = -1;
#pragma omp parallel for schedule(static) reduction(max : missing)
  for (std::int64_t r = 0; r < q; ++r) {
    const std::int64_t* key = request_key + r * d1;
    std::int64_t at = -1;
    for (std::int64_t i = 0; i < nborders && at < 0; ++i) {
      const BlockBorder& b = borders[i];
      if (b.owner != request_owner[r]) continue;
      const auto& idx = sorted[std::size_t(i)];
      auto it = std::lower_bound(
          idx.begin(), idx.end(), key,
          [&](std::int64_t x, const std::int64_t* k) { return less(b.keys + x * d1, k); });
      if (it != idx.end() && std::equal(key, key + d1, b.keys + *it * d1))
        at = b.offset + b.rows[*it];
    }
    if (at < 0)
      missing = std::max(missing, r);
    else
      out[std::size_t(request_pos[r])] = at;
  }
  if (missing >= 0)
    throw Error(ErrorCode::Internal,
                "block_neighbors: request " + std::to_string(missing) + " (owner " +
                    std::to_string(request_owner[missing]) +
                    ") was not found in its owner's border (a bug: please report it with the "
                    "input)");
  return out;
}

}  // namespace gpugeom
