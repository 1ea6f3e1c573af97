// What the public constrained-triangulation entry gets from a backend (internal): the
// constrained Delaunay triangulation of the convex hull, before holes and the outside go.
#pragma once
#include <cstdint>

#include "gpugeom/cdt2d.hpp"

namespace gpugeom::cdt {

// The segments as recovery saw them (Stats counters in cdt2d.cpp).
struct RecoveryCounts {
  std::int64_t kept = 0, zero_length = 0, repeated = 0, recovered = 0, pieces = 0,
               cavity_triangles = 0, antennas = 0, rounds = 0;
  // Two segments (indices into the segments given) that cross at a point inside both: the
  // recovery stopped there (-1: none).
  std::int32_t cross_a = -1, cross_b = -1;
};

// xy: n points and segments: nseg index pairs, on the host (indices checked). Fills r's
// triangles, neighbors, segment_of, duplicate_of, num_duplicates and stats, unless two segments
// cross (rc.cross_a >= 0: r holds nothing).
namespace cpu_impl {
void triangulate(const double* xy, std::int64_t n, const std::int32_t* segments, std::int64_t nseg,
                 const Cdt2dOptions& opt, ConstrainedTriangulation2d& r, RecoveryCounts& rc);
}
namespace cuda_impl {
void triangulate(const double* xy, std::int64_t n, const std::int32_t* segments, std::int64_t nseg,
                 const Cdt2dOptions& opt, ConstrainedTriangulation2d& r, RecoveryCounts& rc);
}

}  // namespace gpugeom::cdt
