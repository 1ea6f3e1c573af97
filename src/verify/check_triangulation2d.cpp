// 2D: a valid triangulation of the convex hull of the input, the Delaunay property, and the
// constrained Delaunay property.
//
// Why these checks suffice: every triangle positively oriented and every edge shared by at most
// two triangles with opposite directions make the triangles a locally injective oriented map;
// a single boundary cycle that only turns left and winds once around makes its image the
// boundary of a convex polygon with degree one, so the triangles tile that polygon exactly
// once. With every input point a vertex, the polygon is the convex hull.
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "verify_common.hpp"

namespace gpugeom::verify {
using namespace detail;

namespace {
// Half-plane of a direction: true for angles in [0, pi). Exact: only comparisons of inputs.
bool upper(const double* from, const double* to) {
  return to[1] > from[1] || (to[1] == from[1] && to[0] > from[0]);
}
}  // namespace

Report check_triangulation2d(const double* p, std::int64_t n, const std::int32_t* t,
                             std::int64_t nt, const std::int32_t* dup_of) {
  Report r;
  if (nt == 0) {
    r.fail("the triangulation has no triangles");
    return r;
  }
  if (!check_cells(r, n, t, nt, 3, dup_of, p, 2)) return r;
  for (std::int64_t c = 0; c < nt; ++c) {
    const double *a = at<2>(p, t[3 * c]), *b = at<2>(p, t[3 * c + 1]), *d = at<2>(p, t[3 * c + 2]);
    int o = pred::orient2d(a, b, d, scratch());
    if (o <= 0)
      return r.fail(cell_name(3, c, t) + (o == 0 ? " is degenerate (collinear)" : " is clockwise")),
             r;
  }
  // Directed edges: each at most once; an edge without its reverse is on the boundary.
  std::unordered_map<std::uint64_t, std::int64_t> dir;
  dir.reserve(std::size_t(nt) * 3 * 2);
  auto key = [](std::uint32_t u, std::uint32_t v) { return (std::uint64_t(u) << 32) | v; };
  for (std::int64_t c = 0; c < nt; ++c)
    for (int j = 0; j < 3; ++j) {
      std::uint32_t u = t[3 * c + j], v = t[3 * c + (j + 1) % 3];
      if (!dir.emplace(key(u, v), c).second)
        return r.fail("edge " + std::to_string(u) + "->" + std::to_string(v) +
                      " is used twice in the same direction (overlapping triangles), by " +
                      cell_name(3, c, t)),
               r;
    }
  std::unordered_map<std::uint32_t, std::uint32_t> next;  // boundary: u -> v
  for (auto& e : dir) {
    std::uint32_t u = std::uint32_t(e.first >> 32), v = std::uint32_t(e.first);
    if (dir.count(key(v, u))) continue;
    if (!next.emplace(u, v).second)
      return r.fail("boundary vertex " + std::to_string(u) +
                    " has two outgoing boundary edges (pinched)"),
             r;
  }
  std::int64_t count = 0, windings = 0;
  std::uint32_t start = next.begin()->first, u = start;
  do {
    auto it = next.find(u);
    if (it == next.end())
      return r.fail("the boundary is not closed at vertex " + std::to_string(u)), r;
    std::uint32_t v = it->second;
    auto jt = next.find(v);
    if (jt == next.end())
      return r.fail("the boundary is not closed at vertex " + std::to_string(v)), r;
    std::uint32_t w = jt->second;
    const double *a = at<2>(p, u), *b = at<2>(p, v), *c = at<2>(p, w);
    if (pred::orient2d(a, b, c, scratch()) < 0)
      return r.fail("the boundary turns right at vertex " + std::to_string(v) +
                    ": the triangulated region is not convex"),
             r;
    if (!upper(a, b) && upper(b, c)) ++windings;
    u = v;
    if (++count > std::int64_t(next.size())) break;
  } while (u != start);
  if (count != std::int64_t(next.size()))
    return r.fail("the boundary consists of more than one cycle (" + std::to_string(next.size()) +
                  " boundary edges, the cycle from vertex " + std::to_string(start) + " has " +
                  std::to_string(count) + ")"),
           r;
  if (windings != 1)
    return r.fail("the boundary winds " + std::to_string(windings) + " times around the region"), r;
  r.notes.push_back(std::to_string(nt) + " triangles, " + std::to_string(next.size()) +
                    " boundary edges: valid triangulation of the convex hull");
  return r;
}

Report check_delaunay2d(const double* p, std::int64_t n, const std::int32_t* t, std::int64_t nt,
                        const std::int32_t* dup_of) {
  Report r = check_triangulation2d(p, n, t, nt, dup_of);
  if (!r.ok || !locally_delaunay(r, p, t, nt, {})) return r;
  r.notes.push_back("every interior edge is locally Delaunay (exact in-circle)");
  return r;
}

// Why these checks suffice: a triangulation in which every edge not on a constraint is locally
// Delaunay is the constrained Delaunay triangulation of its constraints (Lee and Lin 1986,
// Chew 1989), and each segment being a chain of edges makes the segments constraints.
Report check_constrained_delaunay2d(const double* p, std::int64_t n, const std::int32_t* t,
                                    std::int64_t nt, const std::int32_t* segs, std::int64_t nseg,
                                    const std::int32_t* dup_of) {
  Report r = check_triangulation2d(p, n, t, nt, dup_of);
  if (!r.ok) return r;
  // Each vertex's neighbours, from the triangles' edges.
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> nbr;
  for (std::int64_t c = 0; c < nt; ++c)
    for (int j = 0; j < 3; ++j) {  // both ways: a boundary edge is in one triangle only
      const std::uint32_t u = t[3 * c + j], v = t[3 * c + (j + 1) % 3];
      nbr[u].push_back(v);
      nbr[v].push_back(u);
    }
  std::unordered_set<std::uint64_t> on_segment;
  for (std::int64_t k = 0; k < nseg; ++k) {
    const std::int32_t a = segs[2 * k], b = segs[2 * k + 1];
    const std::string name =
        "segment " + std::to_string(k) + " (" + std::to_string(a) + "-" + std::to_string(b) + ")";
    if (a < 0 || b < 0 || a >= n || b >= n)
      return r.fail(name + " names a point outside 0.." + std::to_string(n - 1)), r;
    if ((dup_of && (dup_of[a] >= 0 || dup_of[b] >= 0)) || a == b)
      return r.fail(name + (a == b ? " has zero length" : " ends at a duplicate point")), r;
    const double *pa = at<2>(p, a), *pb = at<2>(p, b);
    if (pa[0] == pb[0] && pa[1] == pb[1]) return r.fail(name + " has zero length"), r;
    // Along the axis where the segment is longer, positions on it are ordered exactly.
    const int d = std::abs(pb[0] - pa[0]) >= std::abs(pb[1] - pa[1]) ? 0 : 1;
    const double sgn = pb[d] > pa[d] ? 1.0 : -1.0;
    std::uint32_t u = std::uint32_t(a);
    for (std::int64_t steps = 0; u != std::uint32_t(b); ++steps) {
      // The edge from u along the segment: a neighbour on the line through a and b, past u
      // and not past b. Two such would be overlapping edges, which the triangulation check
      // excludes.
      const double* pu = at<2>(p, u);
      std::int64_t next = -1;
      for (std::uint32_t w : nbr[u]) {
        const double* pw = at<2>(p, w);
        if (pred::orient2d(pa, pb, pw, scratch()) != 0) continue;
        if ((pw[d] - pu[d]) * sgn > 0 && (pb[d] - pw[d]) * sgn >= 0) next = w;
      }
      if (next < 0 || steps > n)
        return r.fail(name + " is not a chain of edges: no edge leaves vertex " +
                      std::to_string(u) + " along it (an edge crosses it)"),
               r;
      on_segment.insert(undirected(u, std::uint32_t(next)));
      u = std::uint32_t(next);
    }
  }
  if (!locally_delaunay(r, p, t, nt, on_segment)) return r;
  r.notes.push_back(std::to_string(nseg) + " segments, " + std::to_string(on_segment.size()) +
                    " edges on them; every other interior edge is locally Delaunay (exact "
                    "in-circle): the constrained Delaunay triangulation");
  return r;
}

}  // namespace gpugeom::verify
