// For each point, the index of its first copy (itself when it has none). CGAL keeps one copy of
// a repeated point, not always the first; comparisons with CGAL read every copy as the first.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <vector>

namespace gg_test {

// coords(p) returns the point's coordinates as std::array<double, D>.
template <std::size_t D, class Pt, class Coords>
std::vector<std::int32_t> first_copies(const std::vector<Pt>& pts, Coords coords) {
  std::map<std::array<double, D>, std::int32_t> first;
  std::vector<std::int32_t> f(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
    f[i] = first.emplace(coords(pts[i]), std::int32_t(i)).first->second;
  return f;
}

}  // namespace gg_test
