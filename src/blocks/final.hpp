// stars_final (include/gpugeom/blocks.hpp) with a bound on its scans, for the several devices'
// blocks (delaunay_devices.cpp): points on a sphere make every ball inside it span the input,
// and its scan visit every point near the surface (53 s of tests at 10^7 points in 4 blocks,
// against 0.9 s for a single call).
#pragma once
#include <cstdint>

#include "gpugeom/blocks.hpp"

namespace gpugeom::blocks_detail {

// As stars_final, and false also where the scans of all the balls together would visit more
// than `budget` points (< 0: no bound). Deterministic: false exactly where a ball holds a point
// the block lacks or the scans' total passes the budget.
bool stars_final_within(const double* points, int dim, const std::int32_t* simplices,
                        std::int64_t m, const std::uint8_t* test, const BlockBoxes& boxes,
                        const double* all, const CellGrid& bins, const std::int64_t* order,
                        const std::int64_t* cuts, const std::int64_t* held, std::int64_t nheld,
                        const double* extra_lo, const double* extra_hi, std::int64_t nextra,
                        int threads, std::int64_t budget);

}  // namespace gpugeom::blocks_detail
