// Half-edge twins of a triangle soup on an executor (the digital method's sketch, its start and
// any start handed to the 2D Triangulator): half-edge 3t + k runs from vertex k of triangle t to
// vertex k + 1, and its twin is the half-edge of the same undirected edge in the other triangle
// (-1 where the edge has one triangle: the boundary). Found by sorting the undirected edges'
// keys, so the work is a sort and two passes and the result the same on every executor.
#pragma once
#include <thrust/functional.h>

#include <cstdint>

#include "base/hd.hpp"

namespace gpugeom::mesh {

// tri: 3 nt vertex indices (executor memory); twin: 3 nt entries written. Returns the number
// of edges in three triangles or more (no triangulation has one; those keep twin -1 past the
// first two).
template <class Exec>
std::int64_t pair_half_edges(Exec& ex, const std::int32_t* tri, std::int64_t nt,
                             std::int32_t* twin) {
  const std::int64_t nh = 3 * nt;
  if (nh == 0) return 0;
  auto keys = ex.template alloc<std::uint64_t>(std::size_t(nh));
  auto ids = ex.template alloc<std::int32_t>(std::size_t(nh));
  std::uint64_t* K = keys.data();
  std::int32_t* I = ids.data();
  std::int32_t* W = twin;
  ex.for_each_index(
      nh, GG_LAMBDA(std::int64_t e) {
        const std::uint32_t a = std::uint32_t(tri[e]),
                            b = std::uint32_t(tri[e - e % 3 + (e % 3 + 1) % 3]);
        K[e] = a < b ? std::uint64_t(a) << 32 | b : std::uint64_t(b) << 32 | a;
        I[e] = std::int32_t(e);
        W[e] = -1;
      });
  ex.sort_by_key(K, I, nh);
  auto bad = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      nh,
      GG_LAMBDA(std::int64_t i)->std::int64_t {
        const bool starts = i == 0 || K[i - 1] != K[i];
        if (starts && i + 1 < nh && K[i + 1] == K[i]) {
          W[I[i]] = I[i + 1], W[I[i + 1]] = I[i];
          return i + 2 < nh && K[i + 2] == K[i];
        }
        return 0;
      },
      std::int64_t(0), thrust::plus<std::int64_t>(), bad.data());
  std::int64_t nbad = 0;
  ex.to_host(bad.data(), 1, &nbad);
  return nbad;
}

}  // namespace gpugeom::mesh
