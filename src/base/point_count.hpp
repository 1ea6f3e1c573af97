// The check of a point count every capability computed from points makes first (internal).
#pragma once
#include <cstdint>
#include <string>

#include "gpugeom/common.hpp"

namespace gpugeom::detail {

// Refuses a negative n (InvalidArgument), more than `most` points (InvalidInput: "at most
// <most> <per>") and fewer than `least` (DegenerateInput, followed by `needs`, which says what
// the structure needs).
inline void check_point_count(std::int64_t n, std::int64_t least, std::int64_t most,
                              const std::string& per, const std::string& needs) {
  if (n < 0) throw Error(ErrorCode::InvalidArgument, "negative point count");
  if (n > most)
    throw Error(ErrorCode::InvalidInput, "too many points (" + std::to_string(n) + "): at most " +
                                             std::to_string(most) + " " + per);
  if (n < least)
    throw Error(ErrorCode::DegenerateInput, "fewer than " + std::to_string(least) + " points (" +
                                                std::to_string(n) + "): " + needs);
}

}  // namespace gpugeom::detail
