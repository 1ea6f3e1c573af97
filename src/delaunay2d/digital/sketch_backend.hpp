// The digital sketch's work on an executor (sketch.hpp; internal): grid mapping, PBA (the EDT
// module's feature transform on the executor's own arrays), the debris test, and the dual.
#pragma once
#include <cstdint>
#include <vector>

#include "delaunay2d/digital/hull_fill.hpp"
#include "delaunay2d/digital/sketch.hpp"

namespace gpugeom::del2d::digital {

// Alg. 4.3 on the host: the debris (pixels not 8-connected to their site through their colour;
// found on the executor) recoloured as the standard flooding would. debris: those pixels;
// block[18 j + k], k < 9: the colour of the k-th pixel of the 3x3 block around debris[j] (row
// by row, -1 outside the grid), block[18 j + 9 + k]: that colour's site pixel. Returns the
// recoloured pixels as (pixel, colour) pairs, in the order they were recoloured.
std::vector<std::int32_t> recolour_debris(std::int64_t w, std::int64_t h,
                                          const std::vector<std::int32_t>& debris,
                                          const std::vector<std::int32_t>& block);

}  // namespace gpugeom::del2d::digital
