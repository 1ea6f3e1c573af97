/// @file
/// Weighted centroidal Voronoi diagrams of a 2D density image or a 3D density volume (thesis
/// 4.2.7): Lloyd's iteration with the digital Voronoi diagram (PBA) and every cell's weighted
/// centroid computed on the device (column prefix sums, chunk sums stored in the row of the
/// site, segmented reductions), on the GPU or the CPU.
///
/// Sites live on the points of a Voronoi grid (the density's pixels, or `supersample` grid
/// points per pixel along each axis). Each iteration moves every site to the grid point nearest
/// its cell's weighted centroid, and only when that point is strictly nearer the centroid than
/// where the site is: the energy sum_p w(p) |p - site(p)|^2 then never increases (every
/// decision is exact integer arithmetic, with weights quantised to 16 bits of the density's
/// maximum), and the iteration always terminates.
///
/// Coordinates are geometric: (x, y) or (x, y, z) with x the column, y the row, z the slice of
/// the density (C order (slices, rows, cols)); pixel centres at integers.
#pragma once
#include <cstdint>
#include <functional>
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

/// Where a centroidal Voronoi run is, passed to CvdOptions::progress after each iteration.
struct CvdProgress {
  int iteration = 0;       ///< 1-based
  double energy = 0;       ///< of this iteration's Voronoi diagram, before the sites moved
  double max_move = 0;     ///< largest site move of this iteration, in density pixels
  std::int64_t moved = 0;  ///< sites that moved
};

/// Arrays the caller provides for the results (OutBuffer, common.hpp): host memory for
/// centroidal_voronoi, device memory for centroidal_voronoi_device (host memory where it runs on
/// the CPU executor); sites at least dim times the site count, mass at least the site count
/// (checked before they are written; Error(InvalidArgument) naming the array and both lengths).
/// An output written into a caller's array is empty (null) in the result.
struct CvdBuffers {
  OutBuffer<double> sites, mass;
};

/// How centroidal_voronoi runs: the sites (a count or initial positions), iterations, tolerance,
/// progress.
struct CvdOptions : RunOptions {
  std::int64_t num_sites = 1000;      ///< when initial_sites is empty: drawn with probability
                                      ///< proportional to the density, never twice in one place
  std::vector<double> initial_sites;  ///< dim values per site, in density pixels
  int max_iterations = 200;
  double move_tolerance = 0.1;  ///< stop once no site moves farther (density pixels)
  double energy_tolerance = 0;  ///< also stop once energy falls by less than this fraction
  int supersample = 1;          ///< Voronoi grid points per density pixel, along each axis
  std::uint64_t seed = 1;       ///< for the initial sites
  /// Called after every iteration on the host; returning false stops the iteration.
  std::function<bool(const CvdProgress&)> progress;
  CvdBuffers into;  ///< optional
};

/// Statistics of a centroidal Voronoi diagram: RunStats (phases "setup": the density quantised
/// and spread, the first sites drawn; "iterations": Lloyd's iterations) and its counters.
struct CvdStats : RunStats {
  /// The density's grid points (at the options' supersampling), and the sites.
  std::int64_t grid_points = 0, sites = 0;
  /// Lloyd iterations run (as the result's `iterations`).
  std::int64_t iterations = 0;

  std::map<std::string, std::int64_t> counter_map() const override;
};

/// The result of centroidal_voronoi: the sites, their masses and the energy per iteration, in host
/// memory.
struct CvdResult {
  int dim = 2;
  HostVector<double> sites;   ///< dim per site, density pixels
  HostVector<double> mass;    ///< sum of the density over each site's last cell (pixel area
                              ///< units); 0 for a site that shares its grid point with an
                              ///< earlier one
  HostVector<double> energy;  ///< per iteration: sum_p density(p) |p - site(p)|^2 (pixels^2)
  int iterations = 0;
  bool converged = false;  ///< the move (or energy) tolerance was met
  CvdStats stats;
  std::int64_t num_sites = 0;  ///< sites (also where they went into the caller's arrays)
};

/// density: 2D or 3D, finite and non-negative values, not all zero, of any element type
/// (GridView: host memory, read where it is; on the CUDA executor its bytes cross the bus as they
/// are and are checked and quantised on the device). Throws Error(InvalidInput) for bad densities
/// or sites, Error(InvalidArgument) for bad options.
CvdResult centroidal_voronoi(const GridView& density, const CvdOptions& opt = {});
/// The same for a grid read from a file (io::read_grid); defined in gpugeom_io (link
/// gpugeom::gpugeom_io).
CvdResult centroidal_voronoi(const io::Grid& density, const CvdOptions& opt = {});

/// The result of centroidal_voronoi_device: arrays in device memory (host memory on the CPU
/// executor).
struct DeviceCvdResult {
  int dim = 2;
  std::int64_t num_sites = 0;
  std::shared_ptr<double> sites;  ///< dim per site, density pixels (as CvdResult's)
  std::shared_ptr<double> mass;   ///< per site (as CvdResult's)
  HostVector<double> energy;      ///< per iteration, on the host
  int iterations = 0;
  bool converged = false;
  Backend backend = Backend::Cuda;  ///< where the arrays are: Cuda = device memory, Cpu = host
  CvdStats stats;
};
/// The same iteration with the density in device memory and the sites left there, on opt.stream of
/// opt.device: the density must be ready in that stream's order, and the call returns once the
/// result is. Only the iteration's three convergence figures (and the initial draws' pixel
/// numbers) cross the bus. The arrays are device memory of the call's resource
/// (RunOptions::memory), freed when the last copy of their pointer goes (they can be wrapped
/// without a copy by CuPy or PyTorch). With opt.backend == Backend::Cpu the CPU executor runs it on
/// host memory (the same result); otherwise CUDA runs it, whatever GPUGEOM_BACKEND says. Throws
/// Error(Unsupported) where no CUDA device can be used (and the CPU was not asked for), and as
/// centroidal_voronoi otherwise.
DeviceCvdResult centroidal_voronoi_device(const GridView& device_density,
                                          const CvdOptions& opt = {});

/// Stipple drawings of an image: dots at the sites of the weighted centroidal Voronoi diagram of
/// the image's darkness, each dot's area proportional to the darkness of its cell, so the drawing
/// keeps the tone. What `gpugeom stipple` and the Python `gpugeom.stipple` draw.
struct StippleOptions : CvdOptions {
  bool invert = false;  ///< dots where the image is bright
  double contrast = 1;  ///< darkness stretched about mid-grey (> 0)
  double gamma = 1;     ///< darkness^gamma (> 0; above 1 lightens mid-tones)
  double ink = 0.6;     ///< dot area = ink x the darkness summed over its cell (> 0)
};
/// A stipple drawing (stipple): dot positions in pixels and the image's size.
struct Stipple {
  CvdResult cvd;              ///< sites (x = column, y = row, pixel centres at integers), mass
  HostVector<double> radius;  ///< per site, in image pixels: sqrt(ink * mass / pi)
  std::int64_t rows = 0, cols = 0;
};
/// The darkness in [0, 1] of a 2D image (float64, the image's shape): integer images by their
/// type's range (uint8 255, uint16 65535, bool 1), other types as given (scaled by their maximum
/// when it exceeds 1), clamped to [0, 1], inverted unless `invert`, stretched by `contrast` about
/// 0.5, raised to `gamma`. NaN stays NaN (the iteration refuses it).
HostVector<double> stipple_darkness(const GridView& image, bool invert, double contrast,
                                    double gamma);
/// image: 2D, host memory, any element type. Throws Error(InvalidArgument) for a 3D image or
/// options out of range, and as centroidal_voronoi.
Stipple stipple(const GridView& image, const StippleOptions& opt = {});

}  // namespace gpugeom
