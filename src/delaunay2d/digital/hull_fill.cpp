// Pockets between the sketch's boundary and its convex hull, triangulated (hull_fill.hpp).
#include "delaunay2d/digital/hull_fill.hpp"

#include <algorithm>
#include <string>
#include <unordered_map>

#include "delaunay2d/digital/ear_clip.hpp"
#include "gpugeom/common.hpp"

namespace gpugeom::del2d::digital {

namespace {
using Id = std::int32_t;

struct Geo {
  const std::vector<std::int64_t>& x;
  const std::vector<std::int64_t>& y;
  // > 0: a, b, c counter-clockwise (exact: grid coordinates below 2^16 each)
  std::int64_t orient(Id a, Id b, Id c) const {
    return (x[std::size_t(b)] - x[std::size_t(a)]) * (y[std::size_t(c)] - y[std::size_t(a)]) -
           (y[std::size_t(b)] - y[std::size_t(a)]) * (x[std::size_t(c)] - x[std::size_t(a)]);
  }
};

std::uint64_t key(Id a, Id b) {
  return std::uint64_t(std::uint32_t(a)) << 32 | std::uint32_t(b);
}

}  // namespace

void pair_new_half_edges(const std::vector<std::int32_t>& triangles,
                         std::vector<std::int32_t>& twin, std::int64_t first,
                         const std::vector<std::int32_t>& open) {
  auto ends = [&](std::int64_t e) {
    return std::pair{triangles[std::size_t(e)],
                     triangles[std::size_t(e - e % 3 + (e % 3 + 1) % 3)]};
  };
  std::unordered_map<std::uint64_t, std::int32_t> wait;  // (a -> b) unpaired, by (a, b)
  for (std::int32_t e : open) {
    const auto [a, b] = ends(e);
    wait[key(a, b)] = e;
  }
  twin.resize(triangles.size(), -1);
  for (std::int64_t e = 3 * first; e < std::int64_t(triangles.size()); ++e) {
    const auto [a, b] = ends(e);
    const auto it = wait.find(key(b, a));
    if (it != wait.end()) {
      twin[std::size_t(e)] = it->second, twin[std::size_t(it->second)] = std::int32_t(e);
      wait.erase(it);
    } else {
      twin[std::size_t(e)] = -1;
      wait[key(a, b)] = std::int32_t(e);
    }
  }
}

std::int64_t fill_to_hull(const std::vector<std::int64_t>& x, const std::vector<std::int64_t>& y,
                          std::vector<std::int32_t>& triangles, std::vector<std::int32_t>& twin) {
  if (triangles.empty()) return 0;
  const Geo g{x, y};
  // The boundary: half-edges without a twin, the disk on their left.
  std::unordered_map<Id, Id> next;
  std::vector<std::int32_t> open;
  for (std::size_t e = 0; e < triangles.size(); ++e) {
    if (twin[e] >= 0) continue;
    const Id a = triangles[e], b = triangles[e - e % 3 + (e % 3 + 1) % 3];
    open.push_back(std::int32_t(e));
    if (!next.emplace(a, b).second)
      throw Error(ErrorCode::Internal,
                  "digital sketch: the boundary passes vertex " + std::to_string(a) + " twice");
  }
  const std::int64_t first = std::int64_t(triangles.size() / 3);
  // The boundary as one cycle, from its lowest vertex (lowest y, then x: on the hull).
  Id start = next.begin()->first;
  for (const auto& [a, b] : next)
    if (std::make_pair(y[std::size_t(a)], x[std::size_t(a)]) <
        std::make_pair(y[std::size_t(start)], x[std::size_t(start)]))
      start = a;
  std::vector<Id> cycle{start};
  for (Id v = next.at(start); v != start; v = next.at(v)) {
    cycle.push_back(v);
    if (cycle.size() > next.size())
      throw Error(ErrorCode::Internal, "digital sketch: the boundary is not one cycle");
  }
  if (cycle.size() != next.size())
    throw Error(ErrorCode::Internal, "digital sketch: the boundary is more than one cycle");
  // The hull of the boundary's vertices (Andrew's monotone chain, strict turns), as positions
  // in the cycle: a simple counter-clockwise polygon meets its hull vertices in the hull's order,
  // and each boundary stretch between two of them that is not one edge closes a pocket.
  std::vector<std::size_t> order(cycle.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto less = [&](std::size_t i, std::size_t j) {
    const Id a = cycle[i], c = cycle[j];
    return std::make_pair(x[std::size_t(a)], y[std::size_t(a)]) <
           std::make_pair(x[std::size_t(c)], y[std::size_t(c)]);
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<std::size_t> chain;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = chain.size();
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::size_t i = pass == 0 ? order[k] : order[order.size() - 1 - k];
      while (chain.size() >= base + 2 &&
             g.orient(cycle[chain[chain.size() - 2]], cycle[chain.back()], cycle[i]) <= 0)
        chain.pop_back();
      chain.push_back(i);
    }
    chain.pop_back();  // (each pass's last point starts the other)
  }
  std::vector<std::size_t> hull(chain.begin(), chain.end());
  std::sort(hull.begin(), hull.end());  // cycle order (the cycle starts at a hull vertex)
  hull.push_back(cycle.size());         // back to the start
  std::int64_t added = 0;
  for (std::size_t h = 0; h + 1 < hull.size(); ++h) {
    const std::size_t from = hull[h], to = hull[h + 1];
    if (to - from < 2) continue;  // the boundary edge is the hull edge
    // The pocket: the stretch from cycle[from] to cycle[to] with the disk on its left, closed by
    // the hull edge; walked the other way round it is counter-clockwise.
    std::vector<Id> pocket;
    for (std::size_t i = to; i + 1 > from; --i) pocket.push_back(cycle[i % cycle.size()]);
    clip_ears(
        pocket, [&](Id a, Id b, Id c) { return g.orient(a, b, c); },
        [&](Id a, Id b, Id c) {
          triangles.insert(triangles.end(), {a, b, c});
          ++added;
        });
  }
  pair_new_half_edges(triangles, twin, first, open);
  return added;
}

}  // namespace gpugeom::del2d::digital
