// The distance transform compiled for the CPU executor.
#include <chrono>
#include <cuda/atomic>
#include <cstdlib>
#include <functional>
#include <cmath>
#include <string>
#include <type_traits>

#include "base/clock.hpp"
#include "edt/edt_backend.hpp"
#include "edt/edt_device.hpp"
#include "exec/cpu_exec.hpp"
#include "exec/peak.hpp"
#include "exec/grid_input.hpp"

namespace gpugeom::edt::cpu_impl {
using Exec = CpuExec;
using std::sqrt;
// What both modes share, then the passes for each site packing (edt_common.hpp): bit fields
// and raster indices for whole grids; for blocks of slices the same with the slices' z, or
// columns.
#include "edt/impl/outputs.inl"
namespace bits {
#include "edt/impl/pba.inl"
#include "edt/impl/cpu_tiles.inl"
#include "edt/impl/grid_transform.inl"
#include "edt/impl/jfa.inl"
#include "edt/impl/cpu_passes.inl"
#include "edt/impl/run.inl"
}  // namespace bits
namespace linear {
using Layout = LinearLayout;
#include "edt/impl/pba.inl"
#include "edt/impl/cpu_tiles.inl"
#include "edt/impl/grid_transform.inl"
#include "edt/impl/jfa.inl"
#include "edt/impl/cpu_passes.inl"
#include "edt/impl/run.inl"
}  // namespace linear
namespace bits_slices {
using Layout = SlicePlanes<edt::Layout>;
#include "edt/impl/pba.inl"
#include "edt/impl/cpu_tiles.inl"
#include "edt/impl/slices.inl"
}  // namespace bits_slices
namespace linear_slices {
using Layout = SlicePlanes<LinearLayout>;
#include "edt/impl/pba.inl"
#include "edt/impl/cpu_tiles.inl"
#include "edt/impl/slices.inl"
}  // namespace linear_slices
namespace column_slices {
using Layout = ColumnLayout;
#include "edt/impl/pba.inl"
#include "edt/impl/cpu_tiles.inl"
#include "edt/impl/slices.inl"
}  // namespace column_slices
#include "edt/impl/entry.inl"
}  // namespace gpugeom::edt::cpu_impl
