// The Voronoi diagrams' device entries' body (internal): both check the structure they are given
// in the same words and run their table's voronoi on its executor.
#pragma once
#include <cstdint>
#include <string>

#include "gpugeom/common.hpp"

namespace gpugeom::detail {

// voronoi2d_device's and voronoi3d_device's body: checks that tri (`simplices`, ns of them,
// with tri.neighbors and tri.duplicate_of) belongs to the n points p and holds its arrays, then
// runs `table`'s voronoi on tri's executor. what: the structure's name in the messages
// ("triangulation"); parts: its arrays'; options: its options type.
template <class Vor, class Table, class Tri, class Options>
Vor run_device_voronoi(const Table& table, const double* p, std::int64_t n, const Tri& tri,
                       const std::int32_t* simplices, std::int64_t ns, const Options& run,
                       const std::string& what, const std::string& parts,
                       const std::string& options) {
  if (tri.num_points != n)
    throw Error(ErrorCode::InvalidArgument,
                "the " + what + " does not belong to these " + std::to_string(n) + " points");
  if (!simplices || !tri.neighbors || (!tri.duplicate_of && tri.num_duplicates))
    throw Error(ErrorCode::InvalidArgument,
                "the " + what + "'s " + parts +
                    ", neighbours or duplicate map are not in it (were they written into the "
                    "caller's arrays, " +
                    options + "::into?): the Voronoi diagram needs them there");
  Vor v;
  v.num_points = n;
  v.backend = v.stats.backend = tri.backend;
  const std::int32_t* dup = tri.duplicate_of.get();  // (a kept one's may mark removed points)
  table.voronoi(p, n, simplices, tri.neighbors.get(), dup, ns, run, v, v.stats, nullptr, nullptr);
  return v;
}

}  // namespace gpugeom::detail
