/// @file
/// Spatial sorting: the permutation that puts points in Hilbert-curve order.
#pragma once
#include <cstdint>
#include <vector>

#include "gpugeom/common.hpp"

namespace gpugeom {

/// order[k] is the index of the k-th point along the curve. Ties (equal keys) keep input order.
/// Throws Error(InvalidInput) for NaN/Inf coordinates or more than 2^31-1 points.
std::vector<std::int32_t> hilbert_order(const std::vector<Point2>& pts,
                                        Backend backend = Backend::Auto);
/// The same for 3D points.
std::vector<std::int32_t> hilbert_order(const std::vector<Point3>& pts,
                                        Backend backend = Backend::Auto);

}  // namespace gpugeom
