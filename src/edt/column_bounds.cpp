// The first and last site of every column of a host grid (column_site_bounds): the bounds that
// slabs of a grid split along C axis 0 hand each other (EdtSlab). One sweep over the grid on
// host threads, each thread a range of columns through every plane, so that it reads contiguous
// runs of a plane and writes only its own columns. A device grid's: the executor's sweep
// (edt/impl/entry.inl), a thread per column.
#include <omp.h>

#include <algorithm>
#include <string>
#include <type_traits>
#include <utility>

#include "edt/edt_backend.hpp"
#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "exec/grid_input.hpp"
#include "gpugeom/edt.hpp"

namespace gpugeom {

namespace {

template <class T>
bool sweep(const T* data, std::int64_t planes, std::int64_t plane, bool nonzero,
           std::int64_t offset, int threads, ColumnSiteBounds& b) {
  // Ranges of 4096 columns: 32 KiB of each bound per range, within a core's cache.
  constexpr std::int64_t kRange = 4096;
  const std::int64_t ranges = (plane + kRange - 1) / kRange;
  bool finite = true;
  std::int64_t with = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) reduction(&& : finite) \
    reduction(+ : with)
  for (std::int64_t r = 0; r < ranges; ++r) {
    const std::int64_t c0 = r * kRange, c1 = std::min(plane, c0 + kRange);
    std::int64_t* first = b.first.data();
    std::int64_t* last = b.last.data();
    bool nan = false;
    for (std::int64_t z = 0; z < planes; ++z) {
      const T* row = data + z * plane;
      for (std::int64_t c = c0; c < c1; ++c) {
        const T v = row[c];
        if constexpr (std::is_floating_point_v<T>) nan |= v != v;
        if ((v != T(0)) == nonzero) {
          if (first[c] < 0) first[c] = z + offset;
          last[c] = z + offset;
        }
      }
    }
    for (std::int64_t c = c0; c < c1; ++c) with += first[c] >= 0;
    finite = finite && !nan;
  }
  b.columns_with_sites = with;
  return finite;
}

// The grid's planes along axis 0 and elements in a plane, checked.
std::pair<std::int64_t, std::int64_t> planes_of(const GridView& g, const RunOptions& run) {
  if (!g.data) throw Error(ErrorCode::InvalidArgument, "the grid's data pointer is null");
  if (g.shape.empty()) throw Error(ErrorCode::InvalidInput, "the grid has no axes");
  std::int64_t n = 1;
  for (auto e : g.shape) {
    if (e < 1) throw Error(ErrorCode::InvalidInput, "the grid is empty");
    n *= e;
  }
  if (run.threads < 0)
    throw Error(ErrorCode::InvalidArgument, "threads must be 0 (all) or positive");
  return {g.shape[0], n / g.shape[0]};
}

}  // namespace

ColumnSiteBounds column_site_bounds_device(const GridView& g, SiteRule rule, std::int64_t offset,
                                           const RunOptions& run) {
  const auto [planes, plane] = planes_of(g, run);
  const Backend b = device_entry_backend(run.backend, run.device, "column_site_bounds_device");
  if (b == Backend::Cpu) return column_site_bounds(g, rule, offset, run);
  edt::BoundsRequest rq;
  rq.run = run;
  rq.run.backend = b;
  rq.grid = g.data;
  rq.type = g.type;
  rq.rule = rule;
  rq.planes = planes;
  rq.plane = plane;
  rq.offset = offset;
  ColumnSiteBounds r;
  r.first.resize(std::size_t(plane));
  r.last.resize(std::size_t(plane));
  if (GG_ENTRIES(b, edt).column_bounds(rq, r.first.data(), r.last.data()))
    throw Error(ErrorCode::InvalidInput, "the grid contains NaN values");
  r.columns_with_sites = std::int64_t(
      std::count_if(r.first.begin(), r.first.end(), [](std::int64_t f) { return f >= 0; }));
  return r;
}

ColumnSiteBounds column_site_bounds(const GridView& g, SiteRule rule, std::int64_t offset,
                                    const RunOptions& run) {
  const auto [planes, plane] = planes_of(g, run);
  ColumnSiteBounds b;
  b.first.assign(std::size_t(plane), -1);
  b.last.assign(std::size_t(plane), -1);
  const int threads = run.threads > 0 ? run.threads : omp_get_max_threads();
  bool finite = true;
  grid_input::visit(g.type, [&](auto tag) {
    finite = sweep(static_cast<const decltype(tag)*>(g.data), planes, plane,
                   rule == SiteRule::NonZero, offset, threads, b);
  });
  if (!finite) throw Error(ErrorCode::InvalidInput, "the grid contains NaN values");
  return b;
}

}  // namespace gpugeom
