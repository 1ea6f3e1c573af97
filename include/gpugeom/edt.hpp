/// @file
/// Exact Euclidean distance transform, feature transform and digital Voronoi diagram of grids of
/// 2 to 8 axes (the Parallel Banding Algorithm, thesis 4.2; 4.2.6 for more than three axes), on
/// the GPU or the CPU.
///
/// Shapes are in C order, as NumPy has them: (rows, cols), (slices, rows, cols), or any shape of
/// 4 to 8 axes. Sites are the
/// grid points chosen by a mask, or an explicit list of integer coordinates (same axis order).
/// Every voxel gets its nearest site; among equally near sites the one first in raster (C)
/// order wins — so results are deterministic, identical on both backends, and identical
/// between the whole-volume and the slice-by-slice modes. Distances use
/// d^2 = sum_k (sampling_k * delta_k)^2; all comparisons are exact, ties included.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/grid_view.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

namespace io {
struct Grid;  // gpugeom/io.hpp; the overloads taking one are in gpugeom_io
}  // namespace io

/// How the distance transform is computed; every method gives the same exact result.
enum class EdtMethod {
  Pba,  ///< exact
  Jfa,  ///< jump flooding: approximate, kept as a measured baseline only
};

/// Which grid values are sites: NonZero (the Voronoi / feature-transform convention) or Zero
/// (SciPy's distance_transform_edt: distance of every element to the nearest zero).
enum class SiteRule { NonZero, Zero };

/// Output arrays the caller provides (EdtOptions::into): each, when given, must hold exactly the
/// output's element count (count() of the result; features: ndim times that) and be memory of the
/// kind the entry point returns (host for distance_transform, device for
/// distance_transform_device). An output written into a caller's array is absent (empty / null)
/// in the result. A buffer for an output not asked for is refused.
struct EdtBuffers {
  OutBuffer<std::int64_t> sqdist_int;  ///< squared, isotropic
  OutBuffer<double> sqdist_real;       ///< squared, anisotropic
  OutBuffer<float> distance32;
  OutBuffer<double> distance64;
  OutBuffer<std::int32_t> features;
  OutBuffer<std::int32_t> labels;
};

/// One slab of a larger grid (EdtOptions::slab), for transforms split along C axis 0 across
/// processes or devices: the grid given holds the indices [first, first + its extent) along axis
/// 0 of a grid whose axis 0 has `extent` indices (its other axes as the grid given). What lies
/// outside the slab enters only through every column's nearest site on either side — along axis
/// 0 no farther site of a column can be nearer to a voxel of the slab, nor win a tie — so the
/// outputs are exactly those of the whole grid's indices [first, first + extent of the slab),
/// features in the whole grid's coordinates.
struct EdtSlab {
  std::int64_t extent = 0;  ///< the whole grid's extent along axis 0; 0: the grid is not a slab
  std::int64_t first = 0;   ///< the slab's first index along axis 0 in the whole grid
  /// Per column (the slab's elements of one axis-0 index, in C order): the axis-0 index of the
  /// nearest site before `first` (the largest below it), and of the nearest site at or after the
  /// slab's end (the smallest); -1 where the column has none there. One value per column each.
  std::vector<std::int64_t> before, after;
};

/// Per column of a grid (its elements of one index along C axis 0... in C order of the other
/// axes), the first and the last site's index along axis 0, moved by `offset` (a slab's first
/// index in the whole grid), -1 where the column has none: what the slabs on either side of this
/// one need (EdtSlab::before is the last site of the slabs before, after the first of those
/// after). Reads host memory on run.threads host threads (0: all); 1D grids are one column.
/// Throws Error(InvalidInput) for NaN values.
struct ColumnSiteBounds {
  HostVector<std::int64_t> first, last;
  std::int64_t columns_with_sites = 0;
};
/// Every column's (along axis 0) first and last site of a host grid, on host threads: what a slab
/// (EdtOptions::slab) of a larger grid needs from the slabs before and after it. offset is added to
/// the indices.
ColumnSiteBounds column_site_bounds(const GridView& grid, SiteRule rule, std::int64_t offset = 0,
                                    const RunOptions& run = {});
/// The same of a grid in device memory (on run.device and run.stream, as the device entries), the
/// bounds to host arrays; with run.backend == Backend::Cpu the grid is host memory.
ColumnSiteBounds column_site_bounds_device(const GridView& device_grid, SiteRule rule,
                                           std::int64_t offset = 0, const RunOptions& run = {});

/// What distance_transform computes (distances, features, labels; their types), how (method,
/// sampling, slices, slab) and into which of the caller's arrays.
struct EdtOptions : RunOptions {
  EdtMethod method = EdtMethod::Pba;
  std::vector<double> sampling;  ///< per axis, C order; empty = all 1. Positive and finite.
  bool squared = false;          ///< squared distances (int64 when isotropic, else float64)
  int distance = 0;              ///< 0: none, 32: float32 distances, 64: float64 distances
  bool features = false;         ///< nearest site coordinates, SciPy's return_indices layout
  bool labels = false;           ///< index of the nearest site (mask: raster rank of the site)
  /// PBA band counts per axis (x, y, z: the thesis' k1, k2 and the 3D pass); 0 picks them by
  /// size: the smallest power of two that gives the executor enough independent (line, band)
  /// items (its concurrency: 1024 per GPU multiprocessor, 4 per CPU thread) while keeping bands
  /// of at least 16 voxels; at most 64.
  std::int64_t bands[3] = {0, 0, 0};
  /// Tuning for benchmarks and tests; the result never depends on it. window_reach: how far the
  /// windowed passes search a line before handing it to the banded pass (-1: chosen by site
  /// density, 0: never windowed). tiles (CUDA): banded passes in shared-memory tiles (-1: where
  /// they pay, 0: never, 1: wherever they fit).
  std::int64_t window_reach = -1;
  int tiles = -1;
  /// Slice-by-slice mode: about how many voxels of slices are computed together (0: 2^24;
  /// fewer take less device memory, more launches). Tuning too: never changes the result.
  std::int64_t slice_block = 0;
  /// Grids of 3 or more axes: compute just these indices along C axis 0 (slice by slice).
  std::vector<std::int64_t> slices;
  /// Grids of 4 to 8 axes index their sites by 32 bits below 2^32 - 1 voxels, by 64 from there;
  /// true takes 64 bits for any grid (for tests: never changes the result).
  bool wide_indices = false;
  /// A slab of a larger grid (EdtSlab), for a grid's sites (distance_transform and
  /// distance_transform_device; the bounds are host arrays in either): it computes every index of
  /// the slab (no slices), and no labels (a site's rank in the whole grid is unknown here), on
  /// grids of 3 to 8 axes (give a 2D grid as (rows, 1, columns), its sampling as (s0, 1, s1)).
  /// Throws Error(InvalidArgument) otherwise, or where the bounds are out of place.
  EdtSlab slab;
  EdtBuffers into;  ///< caller-provided output arrays (optional)
};

/// Statistics of a distance transform: RunStats (phases "upload", a pass per axis ("pass_x",
/// "pass_y", "pass_z"; "pass_0" ... for 4 to 8 axes; "candidates" first by slices), "transform",
/// "outputs_device", "outputs"; distance_transform_devices: "bounds", "slabs" and each device's
/// own as "slab<i>_<phase>") and its counters, 0 where their step did not run.
struct EdtStats : RunStats {
  /// The banded passes' bands along x, y and z (0 for a pass that ran whole lines).
  std::int64_t bands_x = 0, bands_y = 0, bands_z = 0;
  /// By slices: the slices computed together in one block.
  std::int64_t slices_per_block = 0;
  /// Grids of 4 to 8 axes: the bits of the nearest sites' indices (32 or 64).
  std::int64_t index_bits = 0;
  /// distance_transform_devices: the slabs (one per device).
  std::int64_t slabs = 0;

  std::map<std::string, std::int64_t> counter_map() const override;
};

/// The result of distance_transform, in host memory: the outputs EdtOptions asked for.
struct EdtResult {
  std::vector<std::int64_t> shape;      ///< of the output (slices replace the first extent)
  HostVector<std::int64_t> sqdist_int;  ///< squared distances, isotropic
  HostVector<double> sqdist_real;       ///< squared distances, anisotropic
  HostVector<float> distance32;
  HostVector<double> distance64;
  HostVector<std::int32_t> features;  ///< ndim arrays of count() each (axis 0 first)
  HostVector<std::int32_t> labels;
  EdtStats stats;
  /// The number of grid elements.
  std::int64_t count() const;
};

/// Sites where the grid's values say so (rule). Throws Error(InvalidInput) for a grid without
/// sites or with NaN values, shapes of fewer than 2 or more than 8 axes, whole 2D / 3D grids of
/// 2^32-1 voxels or more (1625^3 is the largest cube; by slices a volume may hold any number,
/// each slice fewer than 2^31-1; grids of 4 to 8 axes may hold any number), extents above 65536
/// (3D and up) or 131072 (2D), or labels asked for more than 2^31-1 sites; Error(OutOfMemory)
/// before any launch for a whole volume whose arrays cannot fit the device (use slices: they hold
/// the sites' list, 8 B a site, 12 with labels, and blocks of slices), or for slices whose sites'
/// list cannot. The grid is read where it is: on the CUDA executor its bytes go to the device as
/// they are (the rule is applied there), so a uint8 or bool grid costs its size over the bus.
EdtResult distance_transform(const GridView& grid, SiteRule rule, const EdtOptions& opt = {});
/// The same for a grid read from a file (io::read_grid); defined in gpugeom_io (link
/// gpugeom::gpugeom_io).
EdtResult distance_transform(const io::Grid& grid, SiteRule rule, const EdtOptions& opt = {});
/// Sites given by coordinates (ndim per site, C order). Duplicates keep the lower index.
EdtResult distance_transform_sites(const std::vector<std::int64_t>& shape,
                                   const std::vector<std::int64_t>& sites,
                                   const EdtOptions& opt = {});

/// The result of distance_transform_device: arrays in device memory (host memory on the CPU
/// executor).
struct DeviceEdtResult {
  std::vector<std::int64_t> shape;  ///< of each output (slices replace the first extent)
  std::shared_ptr<std::int64_t> sqdist_int;
  std::shared_ptr<double> sqdist_real;
  std::shared_ptr<float> distance32;
  std::shared_ptr<double> distance64;
  std::shared_ptr<std::int32_t> features;  ///< ndim arrays of count() each (axis 0 first)
  std::shared_ptr<std::int32_t> labels;
  Backend backend = Backend::Cuda;  ///< where the arrays are: Cuda = device memory, Cpu = host
  EdtStats stats;
  /// The number of grid elements.
  std::int64_t count() const;
};
/// The same transform with the grid in device memory and the outputs left there (or written
/// into the caller's device arrays, EdtOptions::into), on opt.stream of opt.device: the grid must
/// be ready in that stream's order, and the call returns once the outputs are. The library's
/// arrays come from the call's resource (RunOptions::memory) and are freed when the last copy
/// of their pointer goes; they can be wrapped without a copy
/// (CuPy, PyTorch through DLPack). With opt.backend == Backend::Cpu "device" memory is host
/// memory and the CPU executor runs (the same results). Slices (opt.slices) compute only those
/// indices along axis 0 from the whole grid on the device. Throws Error(Unsupported) where the
/// build or the machine has no CUDA device (and the CPU was not asked for), and as
/// distance_transform.
DeviceEdtResult distance_transform_device(const GridView& device_grid, SiteRule rule,
                                          const EdtOptions& opt = {});

}  // namespace gpugeom
