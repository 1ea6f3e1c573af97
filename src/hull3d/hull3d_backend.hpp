// What the public convex hull entry gets back from a backend (internal).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "exec/dynamic_state.hpp"
#include "exec/point_entries.hpp"
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

// One executor's entries (exec/dispatch.hpp, exec/point_entries.hpp): impl/entries.inl fills
// them for each executor.
using Entries = detail::PointEntries<Hull3dOptions, Output, DeviceOutput, Kept>;
GG_DECLARE_TABLE(Entries, entries)

}  // namespace gpugeom::hull3d
