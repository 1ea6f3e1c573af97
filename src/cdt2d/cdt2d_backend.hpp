// What the public constrained-triangulation entries get from a backend (internal).
#pragma once
#include <cstdint>
#include <memory>

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

// A result in the executor's memory: count triangles (3 entries each in triangles, neighbors,
// segment_of; one in attribute, with regions), duplicate_of for every point.
struct DeviceResult {
  std::shared_ptr<std::int32_t> triangles, neighbors, segment_of, duplicate_of;
  std::shared_ptr<double> attribute;
  std::int64_t count = 0, removed = 0, num_duplicates = 0;
};

// xy: n points and segments: nseg index pairs, on the host (indices checked). Fills r's
// triangles, neighbors, segment_of, duplicate_of, num_duplicates, removed_triangles, attribute
// and stats, unless two segments cross (rc.cross_a >= 0: r holds nothing). triangulate_device:
// both in the executor's memory (indices checked there), the result left there.
// One executor's entries (exec/dispatch.hpp), filled by each executor's unit.
struct Entries {
  void (*triangulate)(const double* xy, std::int64_t n, const std::int32_t* segments,
                      std::int64_t nseg, const Cdt2dOptions& opt, ConstrainedTriangulation2d& r,
                      RecoveryCounts& rc);
  void (*triangulate_device)(const double* xy, std::int64_t n, const std::int32_t* segments,
                             std::int64_t nseg, const Cdt2dOptions& opt, DeviceResult& d, Stats& st,
                             RecoveryCounts& rc);
};
namespace cpu_impl {
extern const Entries entries;
}
namespace cuda_impl {
extern const Entries entries;
}

}  // namespace gpugeom::cdt
