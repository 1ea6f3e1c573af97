// What the public refinement entries get from a backend (internal).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "cdt2d/cdt2d_backend.hpp"
#include "gpugeom/refine2d.hpp"

namespace gpugeom::refine {

// The rounds' totals (Stats counters in refine2d.cpp).
struct Tally {
  std::int64_t rounds = 0, splits = 0, points = 0, dropped = 0;
};

// A mesh in the executor's memory (np points, nt triangles), the report lists on the host.
struct DeviceResult {
  std::shared_ptr<double> xy, attribute;
  std::shared_ptr<std::int32_t> tri, nbr, seg, dup;
  std::int64_t np = 0, nt = 0, removed = 0;
  std::vector<std::int32_t> small, large;
  std::vector<std::int8_t> reasons;
};

// refine: host points (n) and segments (nseg pairs, indices checked), final_of_base naming each
// segment's marks in the output; fills r unless two segments cross (rc.cross_a >= 0).
// refine_device: both in the executor's memory, indices checked there, marks the given indices.
#define GG_REFINE_BACKEND                                                                    \
  void refine(const double* xy, std::int64_t n, const std::int32_t* segs, std::int64_t nseg, \
              const std::vector<std::int32_t>& final_of_base, const Refine2dOptions& opt,    \
              RefinedMesh2d& r, cdt::RecoveryCounts& rc, Tally& tally);                      \
  void refine_device(const double* xy, std::int64_t n, const std::int32_t* segs,             \
                     std::int64_t nseg, const Refine2dOptions& opt, DeviceResult& d,         \
                     cdt::RecoveryCounts& rc, Tally& tally);
namespace cpu_impl {
GG_REFINE_BACKEND
}
namespace cuda_impl {
GG_REFINE_BACKEND
}
#undef GG_REFINE_BACKEND

}  // namespace gpugeom::refine
