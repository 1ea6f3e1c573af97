// What the public convex hull entry gets back from a backend (internal).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "exec/dynamic_state.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"
#include "gpugeom/hull3d.hpp"

namespace gpugeom::hull3d {

// The backends fill the public results' fields (their other fields are the public entry's):
// one result type per memory space.
using Output = ConvexHull3d;
using DeviceOutput = DeviceHull3d;

// The facet store grows with the hull (construct.inl): it starts at first_facet_slots(n) slots
// and at most kMaxFacetSlots exist (the neighbour encoding 4 * slot + local index is an int32).
// Tests set a small first size (forced, Tuning::Hull3d) to make every hull grow it many times.
constexpr std::int64_t kMaxFacetSlots = std::int64_t(1) << 29;
std::int64_t first_facet_slots(std::int64_t n, std::int64_t forced = 0);

// The planes the executor could not give in double (NaN), redone in long double on the host: p
// holds the points, t the nf facets, eq their planes (host memory). Defined in hull3d.cpp.
void redo_planes(const double* p, const std::int32_t* t, std::int64_t nf, double* eq);

// DynamicHull3d's state on one executor (impl/dynamic.inl): also the extreme points' count.
class Kept : public detail::KeptUpdates<Output, DeviceOutput> {
 public:
  virtual std::int64_t vertices() const = 0;
};

// Refuses counts no hull can be made of (Error); defined in hull3d.cpp.
void check_count(std::int64_t n);

// One executor's entries (exec/dispatch.hpp): impl/entries.inl fills them for each executor.
// compute: xyz holds n points on the host; compute_device: n points in the executor's memory.
// Both validate the points on the executor (throw Error) and honour opt.into.
struct Entries {
  std::unique_ptr<Kept> (*make_kept)(const Hull3dOptions& opt);
  void (*compute)(const double* xyz, std::int64_t n, const Hull3dOptions& opt, Output& out,
                  Stats& stats);
  void (*compute_device)(const double* xyz, std::int64_t n, const Hull3dOptions& opt,
                         DeviceOutput& out, Stats& stats);
};
namespace cpu_impl {
extern const Entries entries;
}
namespace cuda_impl {
extern const Entries entries;
}

}  // namespace gpugeom::hull3d
