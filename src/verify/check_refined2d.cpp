// 2D: a quality mesh of a domain (refine2d's output), judged without the library's algorithms.
//
// Why these checks suffice for "a constrained Delaunay mesh of the domain that covers the
// segments": positively oriented triangles whose directed edges each occur once form a locally
// injective oriented map; every boundary edge lying on a segment means the mesh ends only at
// segments; every other edge locally Delaunay makes it the constrained Delaunay triangulation of
// its marked edges (Lee and Lin, Chew); and each segment being one path of marked edges from its
// first end to its last, through vertices on it up to rounding, means it is covered.
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "verify_common.hpp"

namespace gpugeom::verify {
using namespace detail;

namespace {
constexpr double kPi = 3.14159265358979323846;

// The smallest angle of a triangle in degrees, and its area (long double: a judge, not a copy of
// the library's arithmetic).
void measure(const double* a, const double* b, const double* c, double& angle, double& area) {
  const long double ux = (long double)b[0] - a[0], uy = (long double)b[1] - a[1];
  const long double vx = (long double)c[0] - a[0], vy = (long double)c[1] - a[1];
  area = double((ux * vy - uy * vx) / 2);
  const double* p[3] = {a, b, c};
  angle = 180;
  for (int k = 0; k < 3; ++k) {
    const double* o = p[k];
    const double* q = p[(k + 1) % 3];
    const double* s = p[(k + 2) % 3];
    const long double x1 = (long double)q[0] - o[0], y1 = (long double)q[1] - o[1];
    const long double x2 = (long double)s[0] - o[0], y2 = (long double)s[1] - o[1];
    const long double ang = std::atan2(std::fabs(x1 * y2 - y1 * x2), x1 * x2 + y1 * y2);
    angle = std::min(angle, double(ang * 180 / kPi));
  }
}
}  // namespace

Report check_refined_mesh2d(const double* p, std::int64_t n, const std::int32_t* t, std::int64_t nt,
                            const std::int32_t* seg_of, const std::int32_t* segs, std::int64_t nseg,
                            const std::int32_t* dup_of, double min_angle, double max_area,
                            const std::int32_t* exempt, std::int64_t nexempt) {
  Report r;
  if (nt == 0) return r.fail("the mesh has no triangles"), r;
  for (std::int64_t c = 0; c < nt; ++c)
    for (int j = 0; j < 3; ++j) {
      const std::int32_t v = t[3 * c + j];
      if (v < 0 || v >= n)
        return r.fail(cell_name(3, c, t) + " names a point outside 0.." + std::to_string(n - 1)), r;
      if (dup_of && dup_of[v] >= 0)
        return r.fail(cell_name(3, c, t) + " uses duplicate point " + std::to_string(v)), r;
      if (v == t[3 * c + (j + 1) % 3]) return r.fail(cell_name(3, c, t) + " repeats a vertex"), r;
    }
  for (std::int64_t c = 0; c < nt; ++c) {
    const int o = pred::orient2d(at<2>(p, t[3 * c]), at<2>(p, t[3 * c + 1]), at<2>(p, t[3 * c + 2]),
                                 scratch());
    if (o <= 0)
      return r.fail(cell_name(3, c, t) + (o == 0 ? " is degenerate (collinear)" : " is clockwise")),
             r;
  }
  // Directed edges once each; an edge without its reverse is on the boundary and must be marked.
  std::unordered_map<std::uint64_t, std::int64_t> dir;
  dir.reserve(std::size_t(nt) * 6);
  for (std::int64_t c = 0; c < nt; ++c)
    for (int j = 0; j < 3; ++j)
      if (!dir.emplace(directed(t[3 * c + j], t[3 * c + (j + 1) % 3]), 3 * c + j).second)
        return r.fail("edge " + std::to_string(t[3 * c + j]) + "->" +
                      std::to_string(t[3 * c + (j + 1) % 3]) +
                      " is used twice in the same direction (overlapping triangles)"),
               r;
  // Half-edge j -> j+1 of triangle c is the edge opposite vertex j + 2.
  auto mark = [&](std::int64_t he) { return seg_of[3 * (he / 3) + (he % 3 + 2) % 3]; };
  std::unordered_set<std::uint64_t> marked;
  std::unordered_map<std::int32_t, std::vector<std::pair<std::uint32_t, std::uint32_t>>> by_seg;
  std::int64_t boundary = 0;
  for (const auto& e : dir) {
    const std::uint32_t u = std::uint32_t(e.first >> 32), v = std::uint32_t(e.first);
    const std::int32_t g = mark(e.second);
    const auto rev = dir.find(directed(v, u));
    if (rev == dir.end()) {
      ++boundary;
      if (g == -1)
        return r.fail("boundary edge " + std::to_string(u) + "-" + std::to_string(v) +
                      " lies on no segment"),
               r;
    } else if (mark(rev->second) != g) {
      return r.fail("edge " + std::to_string(u) + "-" + std::to_string(v) +
                    " is marked differently from its two sides"),
             r;
    }
    if (g != -1) {
      marked.insert(undirected(u, v));
      if (g >= 0 && (rev == dir.end() || u < v)) by_seg[g].push_back({u, v});
    }
  }
  // Each segment: one path of its marked edges from one end to the other, along it.
  for (std::int64_t s = 0; s < nseg; ++s) {
    std::int32_t a = segs[2 * s], b = segs[2 * s + 1];
    if (dup_of && dup_of[a] >= 0) a = dup_of[a];
    if (dup_of && dup_of[b] >= 0) b = dup_of[b];
    const std::string name = "segment " + std::to_string(s);
    auto it = by_seg.find(std::int32_t(s));
    if (a == b) continue;
    if (it == by_seg.end()) {
      // A segment outside the domain (removed with a hole) has no edges; one inside must.
      continue;
    }
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> adj;
    for (auto [u, v] : it->second) adj[u].push_back(v), adj[v].push_back(u);
    for (auto& [v, l] : adj)
      if (l.size() > 2 || (l.size() == 1 && v != std::uint32_t(a) && v != std::uint32_t(b)))
        return r.fail(name + "'s edges do not form one path from its ends (vertex " +
                      std::to_string(v) + ")"),
               r;
    if (!adj.count(std::uint32_t(a)) || !adj.count(std::uint32_t(b)))
      return r.fail(name + "'s edges do not reach both its ends"), r;
    std::uint32_t prev = std::uint32_t(-1), cur = std::uint32_t(a);
    std::size_t steps = 0;
    const double *pa = at<2>(p, a), *pb = at<2>(p, b);
    const double len = std::hypot(pb[0] - pa[0], pb[1] - pa[1]);
    const double scale =
        std::max({std::fabs(pa[0]), std::fabs(pa[1]), std::fabs(pb[0]), std::fabs(pb[1]), len});
    while (cur != std::uint32_t(b)) {
      const auto& l = adj[cur];
      const std::uint32_t next = l[0] != prev ? l[0] : (l.size() > 1 ? l[1] : prev);
      if (next == prev || ++steps > it->second.size())
        return r.fail(name + "'s edges break off at vertex " + std::to_string(cur)), r;
      const double* q = at<2>(p, next);
      const double off =
          std::fabs((pb[0] - pa[0]) * (q[1] - pa[1]) - (pb[1] - pa[1]) * (q[0] - pa[0])) / len;
      if (off > 1e-9 * scale)
        return r.fail(name + " runs through vertex " + std::to_string(next) + ", " +
                      std::to_string(off) + " off its line"),
               r;
      prev = cur, cur = next;
    }
    if (steps != it->second.size()) return r.fail(name + " has marked edges off its path"), r;
  }
  if (!locally_delaunay(r, p, t, nt, marked)) return r;
  // Quality: every triangle not exempt within the bounds (the angle to 1e-9 degrees: points are
  // doubles, the bound is met up to their rounding).
  std::unordered_set<std::int32_t> ex(exempt, exempt + nexempt);
  double worst = 180;
  for (std::int64_t c = 0; c < nt; ++c) {
    double ang, area;
    measure(at<2>(p, t[3 * c]), at<2>(p, t[3 * c + 1]), at<2>(p, t[3 * c + 2]), ang, area);
    if (ex.count(std::int32_t(c))) continue;
    worst = std::min(worst, ang);
    if (min_angle > 0 && ang < min_angle - 1e-9)
      return r.fail(cell_name(3, c, t) + " has an angle of " + std::to_string(ang) +
                    " degrees, below the bound " + std::to_string(min_angle)),
             r;
    if (max_area > 0 && area > max_area * (1 + 1e-12))
      return r.fail(cell_name(3, c, t) + " has area " + std::to_string(area) +
                    ", above the bound " + std::to_string(max_area)),
             r;
  }
  r.notes.push_back(std::to_string(nt) + " triangles, " + std::to_string(boundary) +
                    " boundary edges all on segments, " + std::to_string(nseg) +
                    " segments covered; every other edge locally Delaunay (exact in-circle); "
                    "smallest angle " +
                    std::to_string(worst) + " degrees outside " + std::to_string(nexempt) +
                    " exempt triangles");
  return r;
}

}  // namespace gpugeom::verify
