// The candidates for the global hull's extreme points that every block of the several devices
// holds (delaunay_devices.cpp), found once over all the prepared points where the module
// prepared them (PreparedPoints::hull): in 3D the hull itself (convex_hull3d_device), in 2D the
// octagon filter (hull_rules.hpp). Per block, on host gathers of its own points, this was 50 ms
// in 3D at 10^7 points and 130 ms in 2D at 2·10^7; a superset of the global hull's extreme
// points is all the blocks need (docs/design-notes.md, "Several GPUs of one host").
#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "base/hd.hpp"
#include "blocks/hull_rules.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"
#include "gpugeom/hull3d.hpp"

namespace gpugeom::blocks_detail {

namespace hull_on_detail {
// The extreme point in each of 8 directions (the lowest index where several tie: an order-free
// choice, so any reduction order gives it).
struct Extremes {
  double h[8];
  std::int64_t i[8];
};
struct Higher {
  GG_HD Extremes operator()(const Extremes& a, const Extremes& b) const {
    Extremes r;
    for (int k = 0; k < 8; ++k) {
      const bool first = a.h[k] > b.h[k] || (a.h[k] == b.h[k] && a.i[k] < b.i[k]);
      r.h[k] = first ? a.h[k] : b.h[k];
      r.i[k] = first ? a.i[k] : b.i[k];
    }
    return r;
  }
};
struct Corners {
  double c[16];
  int m;
};
inline HostVector<std::int64_t> all_places(std::int64_t m) {
  HostVector<std::int64_t> out(static_cast<std::size_t>(m));
  for (std::int64_t i = 0; i < m; ++i) out[std::size_t(i)] = i;
  return out;
}
}  // namespace hull_on_detail

// 2D: the places of the m points (2 coordinates each, executor memory) not strictly inside the
// octagon of their extreme points, increasing.
template <class Exec>
HostVector<std::int64_t> hull_filter_on(Exec& ex, const double* pts, std::int64_t m) {
  using namespace hull_on_detail;
  if (m < 4) return all_places(m);
  const Directions8 dir;
  Extremes none;
  for (int k = 0; k < 8; ++k)
    none.h[k] = -std::numeric_limits<double>::infinity(),
    none.i[k] = std::numeric_limits<std::int64_t>::max();
  auto best_b = ex.template alloc<Extremes>(1);
  ex.transform_reduce_into(
      m,
      GG_LAMBDA(std::int64_t i) {
        Extremes e;
        for (int k = 0; k < 8; ++k) e.h[k] = pts[2 * i] * dir.x[k] + pts[2 * i + 1] * dir.y[k];
        for (int k = 0; k < 8; ++k) e.i[k] = i;
        return e;
      },
      none, Higher{}, best_b.data());
  Extremes best;
  ex.to_host(best_b.data(), 1, &best);
  const std::vector<std::int64_t> poly = octagon(best.i);
  if (poly.empty()) return all_places(m);
  Corners c{};
  c.m = int(poly.size());
  for (int v = 0; v < c.m; ++v) ex.to_host(pts + 2 * poly[std::size_t(v)], 2, c.c + 2 * v);
  auto list_b = ex.template alloc<std::int32_t>(std::size_t(m));
  const std::int64_t count = ex.compact_indices(
      m,
      GG_LAMBDA(std::int64_t i) { return !strictly_inside(pts[2 * i], pts[2 * i + 1], c.c, c.m); },
      list_b.data());
  HostVector<std::int32_t> list(static_cast<std::size_t>(count));
  ex.to_host(list_b.data(), count, list.data());
  return HostVector<std::int64_t>(list.begin(), list.end());
}

// 3D: the places of the hull's extreme points of the m points (3 coordinates each, executor
// memory), increasing; all of them where they have no hull (flat). opt: the frame's run options.
template <class Exec>
HostVector<std::int64_t> hull_vertices_on(Exec& ex, const double* pts, std::int64_t m,
                                          const RunOptions& opt) {
  Hull3dOptions h;
  static_cast<RunOptions&>(h) = opt;
  h.backend = Exec::backend;  // (on the frame's device and stream: the points are ready there)
  DeviceHull3d r;
  try {
    r = convex_hull3d_device(pts, m, h);
  } catch (const Error& e) {
    if (e.code() != ErrorCode::DegenerateInput) throw;
    return hull_on_detail::all_places(m);
  }
  HostVector<std::int32_t> v(static_cast<std::size_t>(r.num_vertices));
  ex.to_host(r.vertices.get(), r.num_vertices, v.data());
  HostVector<std::int64_t> out(v.begin(), v.end());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace gpugeom::blocks_detail
