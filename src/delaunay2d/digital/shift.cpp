// The shifting phase's entry (shift.hpp) and the start's whole check, on the host from its
// boundary.
#include "delaunay2d/digital/shift.hpp"

#include <array>
#include <unordered_map>

#include "delaunay2d/digital/convex_turn.hpp"

namespace gpugeom::del2d::digital {

std::string check_start(const std::vector<RimEdge>& rim, const Start& s) {
  // Is the start valid at the points' own coordinates (every vertex is there now): its triangles
  // counter-clockwise (counted on the executor), V - E + F = 1, the boundary one cycle that turns
  // left or goes straight on everywhere and turns once (one lowest vertex)?
  if (s.triangle_count == 0) return "no triangle";
  if (s.not_ccw) return std::to_string(s.not_ccw) + " triangle(s) not counter-clockwise";
  std::unordered_map<std::int32_t, std::int32_t> next;
  std::unordered_map<std::int32_t, std::array<double, 2>> at;
  for (const RimEdge& r : rim) {
    if (!next.emplace(r.a, r.b).second) return "the boundary passes a vertex twice";
    at[r.a] = {r.x, r.y};
  }
  const std::int64_t faces = s.triangle_count;
  const std::int64_t edges = (3 * faces + std::int64_t(next.size())) / 2;
  if (s.vertices - edges + faces != 1) return "not a disk";
  auto below = [](const std::array<double, 2>& a, const std::array<double, 2>& b) {
    return a[1] < b[1] || (a[1] == b[1] && a[0] < b[0]);
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
    const auto &pa = at.at(prev), &pb = at.at(v), &pc = at.at(w->second);
    if (!convex_turn(pa.data(), pb.data(), pc.data())) return "the boundary turns right";
    if (below(pb, pa) && below(pb, pc)) ++lowest;
    prev = v, v = w->second;
    if (++steps > next.size()) return "the boundary is not one cycle";
  } while (v != start);
  if (steps != next.size()) return "the boundary is not one cycle";
  if (lowest != 1) return "the boundary winds more than once";
  return {};
}

}  // namespace gpugeom::del2d::digital
