// The executors' compact_indices write int32 positions: a pass over more than 2^31 - 1 items
// cannot name them all. Checked on the host before the pass, so that a caller that outgrows
// them gets a typed error rather than positions that wrap (CUB's counting iterator wraps
// silently and the predicate then reads before its arrays: 3D Delaunay's hull facets at 10^8
// points did, once, with an illegal address).
#pragma once
#include <cstdint>
#include <string>

#include "gpugeom/common.hpp"

namespace gpugeom::detail {
inline void check_int32_positions(std::int64_t n) {
  if (n > std::int64_t(INT32_MAX))
    throw Error(ErrorCode::Internal,
                "compact_indices over " + std::to_string(n) +
                    " items: their positions do not fit the 32-bit list (a bug in the caller, "
                    "which must go in pieces; please report it)");
}
}  // namespace gpugeom::detail
