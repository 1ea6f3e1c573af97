// Pockets between the sketch's boundary and its convex hull, triangulated (hull_fill.hpp).
#include "delaunay2d/digital/hull_fill.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "delaunay2d/digital/ear_clip.hpp"

namespace gpugeom::del2d::digital {

namespace {
using Id = std::int32_t;

std::uint64_t key(Id a, Id b) {
  return std::uint64_t(std::uint32_t(a)) << 32 | std::uint32_t(b);
}

}  // namespace

HullFill fill_to_hull(const std::vector<RimEdge>& rim, std::int64_t first) {
  HullFill out;
  if (rim.empty()) return out;
  auto no_disk = [&] {
    out.disk = false;
    return out;
  };
  // The boundary's vertices numbered 0..k-1 in rim order (so every test below reads arrays),
  // their grid points, and the boundary as a successor array.
  const std::size_t k = rim.size();
  std::unordered_map<Id, Id> local;
  local.reserve(2 * k);
  std::vector<Id> name(k), succ(k, -1);
  std::vector<std::int64_t> X(k), Y(k);
  for (std::size_t i = 0; i < k; ++i) {
    if (!local.emplace(rim[i].a, Id(i)).second) return no_disk();
    name[i] = rim[i].a, X[i] = std::int64_t(rim[i].x), Y[i] = std::int64_t(rim[i].y);
  }
  for (std::size_t i = 0; i < k; ++i) {
    const auto it = local.find(rim[i].b);
    if (it == local.end()) return no_disk();
    succ[i] = it->second;
  }
  auto x = [&](Id v) { return X[std::size_t(v)]; };
  auto y = [&](Id v) { return Y[std::size_t(v)]; };
  // > 0: a, b, c counter-clockwise (exact: grid coordinates below 2^16 each)
  auto orient = [&](Id a, Id b, Id c) {
    return (x(b) - x(a)) * (y(c) - y(a)) - (y(b) - y(a)) * (x(c) - x(a));
  };
  // The boundary as one cycle, from its lowest vertex (lowest y, then x: on the hull).
  Id start = 0;
  for (Id v = 1; v < Id(k); ++v)
    if (std::make_pair(y(v), x(v)) < std::make_pair(y(start), x(start))) start = v;
  std::vector<Id> cycle{start};
  for (Id v = succ[std::size_t(start)]; v != start; v = succ[std::size_t(v)]) {
    cycle.push_back(v);
    if (cycle.size() > k) return no_disk();
  }
  if (cycle.size() != k) return no_disk();
  // The hull of the boundary's vertices (Andrew's monotone chain, strict turns), as positions
  // in the cycle: a simple counter-clockwise polygon meets its hull vertices in the hull's order,
  // and each boundary stretch between two of them that is not one edge closes a pocket.
  std::vector<std::size_t> order(cycle.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return std::make_pair(x(cycle[i]), y(cycle[i])) < std::make_pair(x(cycle[j]), y(cycle[j]));
  });
  std::vector<std::size_t> chain;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = chain.size();
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::size_t i = pass == 0 ? order[k] : order[order.size() - 1 - k];
      while (chain.size() >= base + 2 &&
             orient(cycle[chain[chain.size() - 2]], cycle[chain.back()], cycle[i]) <= 0)
        chain.pop_back();
      chain.push_back(i);
    }
    chain.pop_back();  // (each pass's last point starts the other)
  }
  std::vector<std::size_t> hull(chain.begin(), chain.end());
  std::vector<char> gone(k, 0);         // the current pocket's clipped vertices
  std::sort(hull.begin(), hull.end());  // cycle order (the cycle starts at a hull vertex)
  hull.push_back(cycle.size());         // back to the start
  for (std::size_t h = 0; h + 1 < hull.size(); ++h) {
    const std::size_t from = hull[h], to = hull[h + 1];
    if (to - from < 2) continue;  // the boundary edge is the hull edge
    // The pocket: the stretch from cycle[from] to cycle[to] with the disk on its left, closed by
    // the hull edge; walked the other way round it is counter-clockwise.
    std::vector<Id> pocket;
    for (std::size_t i = to; i + 1 > from; --i) pocket.push_back(cycle[i % cycle.size()]);
    // Its vertices in buckets of a coarse grid (about one a bucket), so that an ear's test reads
    // the few near it: a pocket along a side of the grid has thousands of vertices.
    std::int64_t x0 = x(pocket[0]), x1 = x0, y0 = y(pocket[0]), y1 = y0;
    for (Id v : pocket)
      x0 = std::min(x0, x(v)), x1 = std::max(x1, x(v)), y0 = std::min(y0, y(v)),
      y1 = std::max(y1, y(v));
    const std::int64_t side = std::max<std::int64_t>(
        1,
        std::int64_t(std::sqrt(double(x1 - x0 + 1) * double(y1 - y0 + 1) / double(pocket.size()))));
    const std::int64_t bw = (x1 - x0) / side + 1, bh = (y1 - y0) / side + 1;
    std::vector<std::int32_t> start_of(static_cast<std::size_t>(bw * bh + 1), 0), in_bucket;
    auto bucket = [&](Id v) { return ((y(v) - y0) / side) * bw + (x(v) - x0) / side; };
    for (Id v : pocket) ++start_of[std::size_t(bucket(v) + 1)];
    for (std::size_t j = 1; j < start_of.size(); ++j) start_of[j] += start_of[j - 1];
    in_bucket.resize(pocket.size());
    {
      std::vector<std::int32_t> fill(start_of.begin(), start_of.end() - 1);
      for (Id v : pocket) in_bucket[std::size_t(fill[std::size_t(bucket(v))]++)] = v;
    }
    // (clipped: a vertex leaves only its own pocket; hull vertices end two pockets and stay)
    clip_ears(
        pocket.data(), std::int64_t(pocket.size()), orient,
        [&](Id a, Id b, Id c) {
          gone[std::size_t(b)] = 1;
          out.triangles.insert(out.triangles.end(),
                               {name[std::size_t(a)], name[std::size_t(b)], name[std::size_t(c)]});
        },
        [&](Id a, Id b, Id c, const Id*, std::int64_t, const auto& visit) {
          const std::int64_t bx0 = (std::min({x(a), x(b), x(c)}) - x0) / side,
                             bx1 = (std::max({x(a), x(b), x(c)}) - x0) / side,
                             by0 = (std::min({y(a), y(b), y(c)}) - y0) / side,
                             by1 = (std::max({y(a), y(b), y(c)}) - y0) / side;
          for (std::int64_t by = by0; by <= by1; ++by)
            for (std::int64_t bx = bx0; bx <= bx1; ++bx) {
              const std::int64_t q = by * bw + bx;
              for (std::int32_t j = start_of[std::size_t(q)]; j < start_of[std::size_t(q + 1)];
                   ++j) {
                const Id v = in_bucket[std::size_t(j)];
                if (!gone[std::size_t(v)] && !visit(v)) return;
              }
            }
        });
    for (Id v : in_bucket) gone[std::size_t(v)] = 0;  // (the pocket's end points end another)
  }
  // Pair the new half-edges with the rim's (reverse direction) and with each other.
  std::unordered_map<std::uint64_t, std::int32_t> wait;  // (a -> b) unpaired, by (a, b)
  for (const RimEdge& r : rim) wait[key(r.a, r.b)] = r.e;
  out.twin.assign(out.triangles.size(), -1);
  for (std::size_t e = 0; e < out.triangles.size(); ++e) {
    const Id a = out.triangles[e], b = out.triangles[e - e % 3 + (e % 3 + 1) % 3];
    const std::int32_t id = std::int32_t(3 * first + std::int64_t(e));
    const auto it = wait.find(key(b, a));
    if (it != wait.end()) {
      out.twin[e] = it->second;
      if (it->second >= 3 * first) out.twin[std::size_t(it->second - 3 * first)] = id;
      wait.erase(it);
    } else {
      wait[key(a, b)] = id;
    }
  }
  return out;
}

}  // namespace gpugeom::del2d::digital
