// The shifting phase's entry (shift.hpp): the rounds on the executor, then the start checked
// whole on the host from its boundary.
#include "delaunay2d/digital/shift.hpp"

#include <unordered_map>

#include "exec/dispatch.hpp"
#include "gpugeom/predicates.hpp"

namespace gpugeom::del2d::digital {

namespace {

// Does the boundary turn left or go straight on at b (a -> b -> c)? (exact)
bool convex_turn(const Point2& a, const Point2& b, const Point2& c) {
  const int o = orient2d(a, b, c);
  if (o != 0) return o > 0;
  auto between = [](double u, double v, double w) { return (u < v && v < w) || (u > v && v > w); };
  return between(a.x, b.x, c.x) || (a.x == b.x && b.x == c.x && between(a.y, b.y, c.y));
}

// Is the start valid at the points' own coordinates (every vertex is there now): its triangles
// counter-clockwise (counted on the executor), V - E + F = 1, the boundary one cycle that turns
// left or goes straight on everywhere and turns once (one lowest vertex)?
std::string check(const double* xy, const Start& s) {
  if (s.triangles.empty()) return "no triangle";
  if (s.not_ccw) return std::to_string(s.not_ccw) + " triangle(s) not counter-clockwise";
  std::unordered_map<std::int32_t, std::int32_t> next;
  for (std::size_t e = 0; e < s.twin.size(); ++e) {
    if (s.twin[e] >= 0) continue;
    const std::int32_t a = s.triangles[e], b = s.triangles[e - e % 3 + (e % 3 + 1) % 3];
    if (!next.emplace(a, b).second) return "the boundary passes a vertex twice";
  }
  const std::int64_t faces = std::int64_t(s.triangles.size() / 3);
  const std::int64_t edges = (3 * faces + std::int64_t(next.size())) / 2;
  if (s.vertices - edges + faces != 1) return "not a disk";
  auto at = [&](std::int32_t i) {
    return Point2{xy[2 * std::int64_t(i)], xy[2 * std::int64_t(i) + 1]};
  };
  auto below = [](const Point2& a, const Point2& b) {
    return a.y < b.y || (a.y == b.y && a.x < b.x);
  };
  const std::int32_t start = next.begin()->first;
  std::int32_t prev = -1;
  for (const auto& [a, b] : next)
    if (b == start) prev = a;
  if (prev < 0) return "the boundary is not a cycle";
  std::size_t steps = 0;
  int lowest = 0;
  std::int32_t v = start;
  do {
    const auto w = next.find(v);
    if (w == next.end()) return "the boundary is not a cycle";
    if (!convex_turn(at(prev), at(v), at(w->second))) return "the boundary turns right";
    if (below(at(v), at(prev)) && below(at(v), at(w->second))) ++lowest;
    prev = v, v = w->second;
    if (++steps > next.size()) return "the boundary is not one cycle";
  } while (v != start);
  if (steps != next.size()) return "the boundary is not one cycle";
  if (lowest != 1) return "the boundary winds more than once";
  return {};
}

}  // namespace

Start shift_sketch(const double* xy, std::int64_t n, const Sketch& s, const RunOptions& run) {
  Start out;
  if (!s.exact) {
    out.reason = "the grid points are not exact doubles";
    return out;
  }
  if (s.triangles.empty()) {
    out.reason = "the sketch has no triangle";
    return out;
  }
  const Backend b = resolve_backend(run.backend, run.device);
  GG_ON_EXECUTOR(b, del2d, digital_shift, xy, n, s, run, out);
  out.reason = check(xy, out);
  out.valid = out.reason.empty();
  return out;
}

}  // namespace gpugeom::del2d::digital
