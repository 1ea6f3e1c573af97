// A caller's grid (GridView) as an executor reads it (internal), shared by the grid capabilities:
// its bytes cross the bus as they are (a host grid on the CUDA executor is uploaded once, in its
// own element type; anything derived from it is computed on the executor), and its elements are
// read through their C++ type.
#pragma once
#include <cstddef>
#include <cstdint>

#include "gpugeom/common.hpp"
#include "gpugeom/scalar_type.hpp"

namespace gpugeom::grid_input {

// f(T{}) with T the element type of `t` (bool grids are read as bytes).
template <class F>
void visit(io::ScalarType t, F&& f) {
  switch (t) {
    case io::ScalarType::Bool:
    case io::ScalarType::U8:
      f(std::uint8_t{});
      return;
    case io::ScalarType::U16:
      f(std::uint16_t{});
      return;
    case io::ScalarType::I32:
      f(std::int32_t{});
      return;
    case io::ScalarType::I64:
      f(std::int64_t{});
      return;
    case io::ScalarType::F32:
      f(float{});
      return;
    case io::ScalarType::F64:
      f(double{});
      return;
  }
}

// The grid's `count` elements where the executor can read them: `grid` itself when it is in the
// executor's memory already (on_device, or the CPU executor), else uploaded into `raw`.
template <class Exec>
const void* on_executor(Exec& ex, const void* grid, std::int64_t count, io::ScalarType t,
                        bool on_device, typename Exec::template Buffer<unsigned char>& raw) {
  if (Exec::backend != Backend::Cuda || on_device) return grid;
  const std::size_t bytes = std::size_t(count) * io::scalar_size(t);
  raw = ex.template alloc<unsigned char>(bytes);
  ex.from_host(static_cast<const unsigned char*>(grid), std::int64_t(bytes), raw.data());
  return raw.data();
}

}  // namespace gpugeom::grid_input
