// Per-backend entry points of the spatial module (internal).
#pragma once
#include <cstdint>

#include "spatial/hilbert.hpp"

namespace gpugeom::cpu_impl {
void hilbert_order(const double* pts, std::int64_t n, int dim, const spatial::Box& box,
                   std::int32_t* order);
}
namespace gpugeom::cuda_impl {
void hilbert_order(const double* pts, std::int64_t n, int dim, const spatial::Box& box,
                   std::int32_t* order);
}
