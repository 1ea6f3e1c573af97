// What the public constrained-triangulation entries get from a backend (internal).
#pragma once
#include <cstdint>
#include <memory>

#include "exec/dispatch.hpp"
#include "gpugeom/cdt2d.hpp"

namespace gpugeom::cdt {

// The segments as recovery saw them (Cdt2dStats' counters, cdt2d.cpp).
struct RecoveryCounts {
  std::int64_t kept = 0, zero_length = 0, repeated = 0, recovered = 0, pieces = 0,
               cavity_triangles = 0, antennas = 0, rounds = 0;
  // Two segments (indices into the segments given) that cross at a point inside both: the
  // recovery stopped there (-1: none).
  std::int32_t cross_a = -1, cross_b = -1;
};

// xy: n points and segments: nseg index pairs, on the host (indices checked). Fills r's
// triangles, neighbors, segment_of, duplicate_of (or opt.into's), num_triangles, num_duplicates,
// removed_triangles, attribute and stats, unless two segments cross (rc.cross_a >= 0: r holds
// nothing). triangulate_device: both in the executor's memory (indices checked there), the result
// left there (or in opt.into's arrays of that memory), its counts and stats likewise.
// One executor's entries (exec/dispatch.hpp), filled by each executor's unit.
struct Entries {
  void (*triangulate)(const double* xy, std::int64_t n, const std::int32_t* segments,
                      std::int64_t nseg, const Cdt2dOptions& opt, ConstrainedTriangulation2d& r,
                      RecoveryCounts& rc);
  void (*triangulate_device)(const double* xy, std::int64_t n, const std::int32_t* segments,
                             std::int64_t nseg, const Cdt2dOptions& opt,
                             DeviceConstrainedTriangulation2d& r, RecoveryCounts& rc);
};
GG_DECLARE_TABLE(Entries, entries)

}  // namespace gpugeom::cdt
