// Exact Euclidean distance transform, feature transform and digital Voronoi diagram of 2D and
// 3D grids (the Parallel Banding Algorithm, thesis 4.2), on the GPU or the CPU.
//
// Shapes are in C order, as NumPy has them: (rows, cols) or (slices, rows, cols). Sites are the
// grid points chosen by a mask, or an explicit list of integer coordinates (same axis order).
// Every voxel gets its nearest site; among equally near sites the one first in raster (C)
// order wins — so results are deterministic, identical on both backends, and identical
// between the whole-volume and the slice-by-slice modes. Distances use
// d^2 = sum_k (sampling_k * delta_k)^2; all comparisons are exact, ties included.
#pragma once
#include <cstdint>
#include <vector>

#include "gpugeom/common.hpp"

namespace gpugeom {

namespace io {
struct Grid;
}

enum class EdtMethod {
  Pba,  // exact
  Jfa,  // jump flooding: approximate, kept as a measured baseline only
};

// Which grid values are sites: NonZero (the Voronoi / feature-transform convention) or Zero
// (SciPy's distance_transform_edt: distance of every element to the nearest zero).
enum class SiteRule { NonZero, Zero };

struct EdtOptions : RunOptions {
  EdtMethod method = EdtMethod::Pba;
  std::vector<double> sampling;  // per axis, C order; empty = all 1. Positive and finite.
  bool squared = false;          // squared distances (int64 when isotropic, else float64)
  int distance = 0;              // 0: none, 32: float32 distances, 64: float64 distances
  bool features = false;         // nearest site coordinates, SciPy's return_indices layout
  bool labels = false;           // index of the nearest site (mask: raster rank of the site)
  // PBA band counts per axis (x, y, z: the thesis' k1, k2 and the 3D pass); 0 picks them by
  // size: the smallest power of two that gives the executor enough independent (line, band)
  // items (its concurrency: 1024 per GPU multiprocessor, 4 per CPU thread) while keeping bands
  // of at least 16 voxels; at most 64.
  std::int64_t bands[3] = {0, 0, 0};
  // Tuning for benchmarks and tests; the result never depends on it. window_reach: how far the
  // windowed passes search a line before handing it to the banded pass (-1: chosen by site
  // density, 0: never windowed). tiles (CUDA): banded passes in shared-memory tiles (-1: where
  // they pay, 0: never, 1: wherever they fit).
  std::int64_t window_reach = -1;
  int tiles = -1;
  std::vector<std::int64_t> slices;  // 3D only: compute just these z slices (slice-by-slice)
};

struct EdtResult {
  std::vector<std::int64_t> shape;       // of the output (slices replace the first extent)
  std::vector<std::int64_t> sqdist_int;  // squared distances, isotropic
  std::vector<double> sqdist_real;       // squared distances, anisotropic
  std::vector<float> distance32;
  std::vector<double> distance64;
  std::vector<std::int32_t> features;  // ndim arrays of count() each (axis 0 first)
  std::vector<std::int32_t> labels;
  Stats stats;
  std::int64_t count() const;
};

// Sites where the mask says so. Throws Error(InvalidInput) for a grid without sites, shapes
// that are not 2D/3D, or sizes whose coordinates do not fit 32 bits together.
EdtResult distance_transform(const io::Grid& grid, SiteRule rule, const EdtOptions& opt = {});
// Sites given by coordinates (ndim per site, C order). Duplicates keep the lower index.
EdtResult distance_transform_sites(const std::vector<std::int64_t>& shape,
                                   const std::vector<std::int64_t>& sites,
                                   const EdtOptions& opt = {});

}  // namespace gpugeom
