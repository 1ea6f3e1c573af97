// The checks of a method's grid option, shared by the modules with a digital method (internal).
#pragma once
#include <cstdint>
#include <string>

#include "gpugeom/common.hpp"

namespace gpugeom::detail {

// grid: 0 (chosen from the input) or lo..hi, and only with Method::Digital. what names the
// grid in the message ("the digital hull's grid side").
inline void check_method_grid(Method method, std::int64_t grid, std::int64_t lo, std::int64_t hi,
                              const char* what) {
  if (grid != 0 && (grid < lo || grid > hi))
    throw Error(ErrorCode::InvalidArgument, std::string("grid: ") + what + " must be " +
                                                std::to_string(lo) + ".." + std::to_string(hi) +
                                                " (or 0: chosen from the point count), got " +
                                                std::to_string(grid));
  if (grid != 0 && method != Method::Digital)
    throw Error(ErrorCode::InvalidArgument, "grid: only Method::Digital uses a grid");
}

}  // namespace gpugeom::detail
