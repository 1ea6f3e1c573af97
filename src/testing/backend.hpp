// The test entries' work on each executor (testing.hpp; impl/entries.inl lists them once).
#pragma once
#include "testing/testing.hpp"

namespace gpugeom::testing {
namespace cpu_impl {
#include "testing/impl/entries.inl"
}  // namespace cpu_impl
namespace cuda_impl {
#include "testing/impl/entries.inl"
}  // namespace cuda_impl
}  // namespace gpugeom::testing
