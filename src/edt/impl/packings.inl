// The passes compiled once for each site packing (edt_common.hpp): N-D grids by 32- and 64-bit
// raster indices (nd.inl); bit fields and raster indices for whole 2D / 3D grids; for blocks of
// slices the same with the slices' z, or columns. Included by edt_cpu.cpp and edt_cuda.cu inside
// their executor's namespace, after GG_EDT_TILES and GG_EDT_PASSES name the executor's own tiled
// and whole-grid passes.
#include "edt/impl/outputs.inl"
#include "edt/impl/columns.inl"
namespace bits {
#include "edt/impl/pba.inl"
#include GG_EDT_TILES
#include "edt/impl/grid_transform.inl"
#include "edt/impl/jfa.inl"
#include GG_EDT_PASSES
#include "edt/impl/run.inl"
}  // namespace bits
namespace linear {
using Layout = LinearLayout;
#include "edt/impl/pba.inl"
#include GG_EDT_TILES
#include "edt/impl/grid_transform.inl"
#include "edt/impl/jfa.inl"
#include GG_EDT_PASSES
#include "edt/impl/run.inl"
}  // namespace linear
namespace nd32 {
using S = std::uint32_t;
#include "edt/impl/nd.inl"
}  // namespace nd32
namespace nd64 {
using S = std::uint64_t;
#include "edt/impl/nd.inl"
}  // namespace nd64
namespace bits_slices {
using Layout = SlicePlanes<edt::Layout>;
#include "edt/impl/pba.inl"
#include GG_EDT_TILES
#include "edt/impl/slices.inl"
}  // namespace bits_slices
namespace linear_slices {
using Layout = SlicePlanes<LinearLayout>;
#include "edt/impl/pba.inl"
#include GG_EDT_TILES
#include "edt/impl/slices.inl"
}  // namespace linear_slices
namespace column_slices {
using Layout = ColumnLayout;
#include "edt/impl/pba.inl"
#include GG_EDT_TILES
#include "edt/impl/slices.inl"
}  // namespace column_slices
#include "edt/impl/entry.inl"
