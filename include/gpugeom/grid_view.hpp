/// @file
/// A grid the caller holds, as the grid capabilities (distance transform, centroidal Voronoi
/// diagram) read it without a copy on the host.
#pragma once
#include <cstdint>
#include <vector>

#include "gpugeom/scalar_type.hpp"

namespace gpugeom {

/// `data` points to the product of `shape` elements of `type`, in C order and native byte order:
/// host memory for the host entry points, device memory for the *_device ones (host memory again
/// where those run on the CPU executor).
struct GridView {
  const void* data = nullptr;
  ScalarType type = ScalarType::U8;
  std::vector<std::int64_t> shape;
};

}  // namespace gpugeom
