/// @file
/// Block-level pieces of the distributed Delaunay triangulation (issue 51): what one block of
/// `gpugeom.dask.delaunay` runs over all its simplices, in C++ so that the per-simplex arithmetic
/// does not cost NumPy temporaries (docs/design-notes.md, "Distributed Delaunay on Dask").
#pragma once
#include <cstdint>

namespace gpugeom {

/// The boxes of a block's finality test, in the first `dim` entries (2 or 3): `region` is the
/// closed box whose points the block holds, `bounds` the closed box of all points, and `scale`
/// the largest coordinate magnitude of `bounds` (the rounding of a centre is bounded relative
/// to it).
struct BlockBoxes {
  double region_lo[3] = {}, region_hi[3] = {};
  double bounds_lo[3] = {}, bounds_hi[3] = {};
  double scale = 0.0;
};

/// For `count` simplices of `points` (row-major, `dim` coordinates a point): simplex i has the
/// `dim` + 1 vertex indices `simplices[(rows ? rows[i] : i) * (dim + 1) + k]`. Writes
/// inside[i] = 1 where the simplex's closed circumball, grown by a bound of the rounding of its
/// centre and radius, misses every part of `bounds` beyond `region`: no point outside the
/// region can lie in it. Writes 0 where it may reach such a point or its centre is not trusted
/// (a singular simplex, or one whose condition number exceeds 1e10). Conservative: a 0 is not
/// a verdict, the caller tests those simplices further. Runs on `threads` host threads (0:
/// OpenMP's default). Throws Error(InvalidArgument) for a dim other than 2 or 3.
void circumballs_inside_region(const double* points, int dim, const std::int64_t* simplices,
                               const std::int64_t* rows, std::int64_t count,
                               const BlockBoxes& boxes, std::uint8_t* inside, int threads = 0);

}  // namespace gpugeom
