// The furthest-site Delaunay triangulation of 2D points (issue 49; SciPy's furthest_site=True):
// the projection of the upper hull of the points lifted to the paraboloid, computed with the
// exact in-circle test instead of a rounded lift.
//
// Only the extreme points of the convex hull are its vertices (convex_hull2d_vertices, exact).
// Their convex polygon is triangulated by Chew's method, turned over: the vertices are taken out
// of the polygon one by one (in a fixed pseudo-random order), then put back in reverse, each
// between the two neighbours it had when it went, as a triangle on the polygon's edge between
// them; an edge whose far vertex lies outside the new triangle's circle is flipped (a furthest-site
// triangle's circle holds every point), and the flips spread as in incremental Delaunay. Points
// on one circle keep the edge they have (no flip on a tie), so the result is one of the valid
// triangulations, the same on every run.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/predicates.hpp"
#include "gpugeom/removed.hpp"

namespace gpugeom {
namespace {

struct Fan {
  const double* xy;
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> opposite;  // edge a->b: third

  Point2 p(std::int32_t i) const { return {xy[2 * i], xy[2 * i + 1]}; }
  void add(std::int32_t a, std::int32_t b, std::int32_t c) {  // counter-clockwise
    opposite[{a, b}] = c, opposite[{b, c}] = a, opposite[{c, a}] = b;
  }
  void drop(std::int32_t a, std::int32_t b, std::int32_t c) {
    opposite.erase({a, b}), opposite.erase({b, c}), opposite.erase({c, a});
  }
  // Triangle (a, b, v), v new: its edge a-b must see the far vertex inside or on its circle.
  void legalise(std::int32_t a, std::int32_t b, std::int32_t v) {
    std::vector<std::pair<std::int32_t, std::int32_t>> todo{{a, b}};
    while (!todo.empty()) {
      const auto [s, t] = todo.back();
      todo.pop_back();
      const auto it = opposite.find({t, s});
      if (it == opposite.end()) continue;  // (a polygon edge)
      const std::int32_t x = it->second;
      const auto mine = opposite.find({s, t});
      if (mine == opposite.end() || mine->second != v) continue;  // (flipped away already)
      if (incircle(p(s), p(t), p(v), p(x)) >= 0) continue;
      drop(s, t, v);
      drop(t, s, x);
      add(s, x, v);
      add(x, t, v);
      todo.push_back({s, x});
      todo.push_back({x, t});
    }
  }
};

}  // namespace

Triangulation2d furthest_site_delaunay2d(const double* xy, std::int64_t n,
                                         const Delaunay2dOptions& opt) {
  Delaunay2dOptions o = opt;
  o.into = {};
  const Triangulation2d dt = delaunay2d(xy, n, o);  // (its boundary gives the extreme points)
  const HostVector<std::int32_t> hull =
      convex_hull2d_vertices(xy, n, dt.triangles.data(), dt.neighbors.data(), dt.num_triangles);
  const std::int64_t h = std::int64_t(hull.size());
  if (h < 3)
    throw Error(ErrorCode::DegenerateInput,
                "the points' convex hull has fewer than 3 extreme points: no furthest-site "
                "triangulation");
  // removal order: positions 3 .. h - 1 of the polygon in a fixed pseudo-random order (expected
  // O(h log h) flips), the first three kept
  std::vector<std::int64_t> order;
  for (std::int64_t k = 3; k < h; ++k) order.push_back(k);
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  for (std::size_t k = order.size(); k > 1; --k) {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    std::swap(order[k - 1], order[std::size_t(state % k)]);
  }
  std::vector<std::int64_t> prev(static_cast<std::size_t>(h)), next(static_cast<std::size_t>(h));
  for (std::int64_t k = 0; k < h; ++k) prev[k] = (k + h - 1) % h, next[k] = (k + 1) % h;
  std::vector<std::pair<std::int64_t, std::int64_t>> around(static_cast<std::size_t>(h));
  for (std::size_t r = order.size(); r-- > 0;) {  // (removed last-to-first, put back first-first)
    const std::int64_t k = order[r];
    around[k] = {prev[k], next[k]};
    next[prev[k]] = next[k], prev[next[k]] = prev[k];
  }
  Fan f{xy, {}};
  {
    std::vector<std::int64_t> left;  // (the three kept, in polygon order)
    for (std::int64_t k = 0; k < 3; ++k) left.push_back(k);
    f.add(hull[left[0]], hull[left[1]], hull[left[2]]);
  }
  for (std::int64_t k : order) {
    const std::int32_t u = hull[around[k].first], w = hull[around[k].second], v = hull[k];
    f.add(w, u, v);
    f.legalise(w, u, v);
  }
  // the triangles, each once (from its smallest vertex's edge), and their neighbours
  Triangulation2d r;
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> tri_of;
  std::vector<std::int32_t> tris;
  for (const auto& [e, c] : f.opposite) {
    const std::int32_t a = e.first, b = e.second;
    if (a > b || a > c) continue;
    const std::int32_t t = std::int32_t(tris.size() / 3);
    tris.insert(tris.end(), {a, b, c});
    tri_of[{a, b}] = tri_of[{b, c}] = tri_of[{c, a}] = t;
  }
  const std::int64_t nt = std::int64_t(tris.size() / 3);
  r.triangles.resize(tris.size());
  r.neighbors.resize(tris.size());
  for (std::int64_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      r.triangles[3 * t + k] = tris[3 * t + k];
      const std::int32_t a = tris[3 * t + (k + 1) % 3], b = tris[3 * t + (k + 2) % 3];
      const auto it = tri_of.find({b, a});
      r.neighbors[3 * t + k] = it == tri_of.end() ? -1 : it->second;
    }
  r.num_triangles = nt;
  // copies keep their twin; the other points that are no vertex are marked as removed ones are
  // (kRemovedPoint: no cell in the diagram)
  std::vector<char> vertex(std::size_t(n), 0);
  for (std::int32_t v : hull) vertex[std::size_t(v)] = 1;
  r.duplicate_of.resize(std::size_t(n));
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int32_t d = dt.duplicate_of[i];
    r.duplicate_of[i] = vertex[std::size_t(i)]               ? -1
                        : (d >= 0 && vertex[std::size_t(d)]) ? d
                                                             : kRemovedPoint;
  }
  r.num_duplicates = dt.num_duplicates;
  r.stats = dt.stats;
  r.stats.furthest_site_vertices = h;
  return r;
}

}  // namespace gpugeom
