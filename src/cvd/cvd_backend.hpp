// What the public CVD entry hands to a backend, and what it gets back (internal).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "edt/edt_common.hpp"
#include "exec/dispatch.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/cvd.hpp"
#include "gpugeom/host_vector.hpp"
#include "gpugeom/scalar_type.hpp"

namespace gpugeom::cvd {

constexpr double kLevels = 65535;  // weights are quantised to 16 bits of the density's maximum

struct Scalars {  // one iteration's convergence figures: the only copy back per iteration
  double energy;
  std::uint64_t max_move2;  // largest squared move, grid units
  std::uint64_t moved;
};

struct Request {
  edt::Layout layout;  // the Voronoi grid (internal axes x, y, z)
  // The density as the caller holds it: pixels of `type` in C order, in the executor's memory
  // where on_device. pext: pixel extents along x, y, z (z = 1 in 2D); each pixel covers s^nd
  // grid points. The backend checks it (finite, non-negative, not all zero) and quantises it.
  const void* density = nullptr;
  io::ScalarType type = io::ScalarType::F64;
  bool on_device = false;
  std::int64_t pext[3] = {1, 1, 1};
  int s = 1;
  // Initial sites in grid coordinates (nd per site, internal axis order), or empty: num_sites
  // drawn from the density with seed.
  std::vector<std::int32_t> sites;
  std::int64_t num_sites = 0;
  std::uint64_t seed = 1;
  RunOptions run;
  int max_iterations = 0;
  double move_tol2 = 0;   // squared, grid units
  double energy_tol = 0;  // relative
  // After each iteration; false stops.
  std::function<bool(int iteration, const Scalars&)> progress;
  bool device_out = false;  // results left in the executor's memory (dev_*)
  CvdBuffers into;          // the caller's arrays, where given
};

struct Output {
  // Final sites (nd per site, density pixels) and the mass of their last cells (density times
  // pixel area): on the host, or left on the executor (device_out).
  HostVector<double> sites, mass;
  std::shared_ptr<double> dev_sites, dev_mass;
  std::int64_t num_sites = 0;
  std::vector<double> energy;  // per iteration, quantised weight units
  double unit_energy = 0;      // what one unit of `energy` is in density times pixels^2
  int iterations = 0;
  bool converged = false;
};

// One executor's entries (exec/dispatch.hpp), filled by each executor's unit.
struct Entries {
  void (*lloyd)(const Request& rq, Output& out, CvdStats& stats);
};
GG_DECLARE_TABLE(Entries, entries)

}  // namespace gpugeom::cvd
