// Weighted centroidal Voronoi diagrams of a 2D density image or a 3D density volume (thesis
// 4.2.7): Lloyd's iteration with the digital Voronoi diagram (PBA) and every cell's weighted
// centroid computed on the device (column prefix sums, chunk sums stored in the row of the
// site, segmented reductions), on the GPU or the CPU.
//
// Sites live on the points of a Voronoi grid (the density's pixels, or `supersample` grid
// points per pixel along each axis). Each iteration moves every site to the grid point nearest
// its cell's weighted centroid, and only when that point is strictly nearer the centroid than
// where the site is: the energy sum_p w(p) |p - site(p)|^2 then never increases (every
// decision is exact integer arithmetic, with weights quantised to 16 bits of the density's
// maximum), and the iteration always terminates.
//
// Coordinates are geometric: (x, y) or (x, y, z) with x the column, y the row, z the slice of
// the density (C order (slices, rows, cols)); pixel centres at integers.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

namespace io {
struct Grid;
}

struct CvdProgress {
  int iteration = 0;       // 1-based
  double energy = 0;       // of this iteration's Voronoi diagram, before the sites moved
  double max_move = 0;     // largest site move of this iteration, in density pixels
  std::int64_t moved = 0;  // sites that moved
};

struct CvdOptions : RunOptions {
  std::int64_t num_sites = 1000;      // when initial_sites is empty: drawn with probability
                                      // proportional to the density, never twice in one place
  std::vector<double> initial_sites;  // dim values per site, in density pixels
  int max_iterations = 200;
  double move_tolerance = 0.1;  // stop once no site moves farther (density pixels)
  double energy_tolerance = 0;  // also stop once energy falls by less than this fraction
  int supersample = 1;          // Voronoi grid points per density pixel, along each axis
  std::uint64_t seed = 1;       // for the initial sites
  // Called after every iteration on the host; returning false stops the iteration.
  std::function<bool(const CvdProgress&)> progress;
};

struct CvdResult {
  int dim = 2;
  HostVector<double> sites;   // dim per site, density pixels
  HostVector<double> mass;    // sum of the density over each site's last cell (pixel area
                              // units); 0 for a site that shares its grid point with an
                              // earlier one
  HostVector<double> energy;  // per iteration: sum_p density(p) |p - site(p)|^2 (pixels^2)
  int iterations = 0;
  bool converged = false;  // the move (or energy) tolerance was met
  Stats stats;
  std::int64_t size() const { return dim ? std::int64_t(sites.size()) / dim : 0; }
};

// density: 2D or 3D, finite and non-negative values, not all zero. Throws Error(InvalidInput)
// for bad densities or sites, Error(InvalidArgument) for bad options.
CvdResult centroidal_voronoi(const io::Grid& density, const CvdOptions& opt = {});

}  // namespace gpugeom
