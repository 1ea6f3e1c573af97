// The digital sketch's work on an executor (sketch.hpp; internal): grid mapping, PBA (the EDT
// module's feature transform on the executor's own arrays), the debris test, and the dual.
#pragma once
#include <cstdint>
#include <vector>

#include "delaunay2d/digital/sketch.hpp"

namespace gpugeom::del2d::digital {

// Alg. 4.3 on the host over a whole colouring (point per pixel; pixel per point): the debris
// (pixels not 8-connected to their site through their colour) recoloured as the standard
// flooding would. Returns the pixels recoloured. Used where the executor found a pixel with no
// neighbour of its colour nearer its site (which debris needs): rare.
std::int64_t recolour_debris(std::int64_t w, std::int64_t h, const std::vector<std::int32_t>& pixel,
                             std::vector<std::int32_t>& colour);

}  // namespace gpugeom::del2d::digital

namespace gpugeom::del2d {
// s holds the frame (width, height, ox, oy, h); fills pixel, missing, site_of, debris, pinched,
// triangles (the dual, before the hull fill), colour where keep_colour, and phase times.
namespace cpu_impl {
void digital_sketch_dual(const double* xy, std::int64_t n, const RunOptions& run, bool keep_colour,
                         digital::Sketch& s);
}
namespace cuda_impl {
void digital_sketch_dual(const double* xy, std::int64_t n, const RunOptions& run, bool keep_colour,
                         digital::Sketch& s);
}
}  // namespace gpugeom::del2d
