// The domain of a constrained triangulation (internal to cdt2d): holes and the outside removed
// by flood fills that stop at segments, regions' attributes spread the same way, and the arrays
// compacted (Triangle's semantics for .poly files).
#pragma once
#include <cstdint>
#include <vector>

#include "gpugeom/cdt2d.hpp"

namespace gpugeom::cdt {

// tris / nbrs / segs: the nt triangles of the convex hull's triangulation (3 entries per triangle
// each); r receives the kept triangles, their neighbours (-1 across a removed one), segment marks
// and attributes.
void apply_domain(const double* xy, std::int64_t n, const std::int32_t* tris,
                  const std::int32_t* nbrs, const std::int32_t* segs, std::int64_t nt,
                  const Cdt2dOptions& opt, ConstrainedTriangulation2d& r);

}  // namespace gpugeom::cdt
