/// @file
/// What the triangulations that follow their points (DynamicDelaunay2d, DynamicDelaunay3d) mark a
/// removed point with.
#pragma once
#include <cstdint>

namespace gpugeom {

/// duplicate_of's entry for a point removed from a triangulation that follows its points
/// (DynamicDelaunay2d / DynamicDelaunay3d::remove): it keeps its index but is no vertex. (A
/// duplicate's entry is the index of its first copy, a vertex's is -1.)
constexpr std::int32_t kRemovedPoint = -2;

}  // namespace gpugeom
