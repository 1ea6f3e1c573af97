// What the public refinement entries get from a backend (internal).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "cdt2d/cdt2d_backend.hpp"
#include "exec/dispatch.hpp"
#include "gpugeom/refine2d.hpp"

namespace gpugeom::refine {

// The rounds' totals (Refine2dStats' counters, refine2d.cpp) and where their time went (measured at
// the host reads the rounds make anyway: no synchronisation of their own).
struct Tally {
  std::int64_t rounds = 0, splits = 0, points = 0, rejected = 0, flips = 0, flip_passes = 0;
  double cdt_ms = 0, decide_ms = 0, insert_ms = 0, output_ms = 0;
};

// refine: host points (n) and segments (nseg pairs, indices checked), final_of_base naming each
// segment's marks in the output; fills r (its arrays, or opt.into's, its counts) unless two
// segments cross (rc.cross_a >= 0).
// refine_device: both in the executor's memory, indices checked there, marks the given indices;
// fills r's arrays and counts (its backend and stats are the public entry's).
// One executor's entries (exec/dispatch.hpp), filled by each executor's unit.
struct Entries {
  void (*refine)(const double* xy, std::int64_t n, const std::int32_t* segs, std::int64_t nseg,
                 const std::vector<std::int32_t>& final_of_base, const Refine2dOptions& opt,
                 RefinedMesh2d& r, cdt::RecoveryCounts& rc, Tally& tally);
  void (*refine_device)(const double* xy, std::int64_t n, const std::int32_t* segs,
                        std::int64_t nseg, const Refine2dOptions& opt, DeviceRefinedMesh2d& r,
                        cdt::RecoveryCounts& rc, Tally& tally);
};
GG_DECLARE_TABLE(Entries, entries)

}  // namespace gpugeom::refine
