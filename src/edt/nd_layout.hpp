// The shape of a request for a grid of 4 to 8 axes, as the entry checks it and hands it to the
// executors (their layout, impl/nd.inl's NdL, is built from it there).
#pragma once
#include <cstdint>

#include "edt/edt_common.hpp"

namespace gpugeom::edt {

// The shape of an N-D request, internal axis order (axis 0 = C's last), as the entry checks it.
struct NdShape {
  int nd = 0;  // 0: not an N-D request
  std::int64_t n[kMaxAxes] = {1, 1, 1, 1, 1, 1, 1, 1};
  bool wide = false;  // 64-bit site indices
  std::int64_t count() const {
    std::int64_t c = 1;
    for (int k = 0; k < nd; ++k) c *= n[k];
    return c;
  }
};

}  // namespace gpugeom::edt
