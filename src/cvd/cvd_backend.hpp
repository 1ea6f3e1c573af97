// What the public CVD entry hands to a backend, and what it gets back (internal).
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "edt/edt_common.hpp"
#include "gpugeom/common.hpp"

namespace gpugeom::cvd {

struct Scalars {  // one iteration's convergence figures: the only copy back per iteration
  double energy;
  std::uint64_t max_move2;  // largest squared move, grid units
  std::uint64_t moved;
};

struct Request {
  edt::Layout layout;                  // the Voronoi grid (internal axes x, y, z)
  std::vector<std::uint32_t> weights;  // per grid point, quantised (< 2^16), raster order
  std::vector<std::int32_t> sites;     // nd per site, grid coordinates, internal axis order
  RunOptions run;
  int max_iterations = 0;
  double move_tol2 = 0;   // squared, grid units
  double energy_tol = 0;  // relative
  // After each iteration; false stops.
  std::function<bool(int iteration, const Scalars&)> progress;
};

struct Output {
  std::vector<std::int32_t> sites;  // final positions, as in the request
  std::vector<std::uint64_t> mass;  // per site, last cells, quantised weight units
  std::vector<double> energy;       // per iteration, quantised weight units
  int iterations = 0;
  bool converged = false;
};

namespace cpu_impl {
void lloyd(const Request& rq, Output& out, Stats& stats);
}
namespace cuda_impl {
void lloyd(const Request& rq, Output& out, Stats& stats);
}

}  // namespace gpugeom::cvd
