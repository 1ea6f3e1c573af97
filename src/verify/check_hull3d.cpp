// 3D convex hull: closed oriented genus-0 surface, convex at every edge, containing every input
// point, with only extreme points as vertices.
#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "verify_common.hpp"

namespace gpugeom::verify {
using namespace detail;

namespace {
bool collinear3(const double* a, const double* b, const double* c) {
  for (int i = 0; i < 3; ++i) {  // collinear iff every coordinate-plane projection is
    const int x = i, y = (i + 1) % 3;
    const double pa[2] = {a[x], a[y]}, pb[2] = {b[x], b[y]}, pc[2] = {c[x], c[y]};
    if (pred::orient2d(pa, pb, pc, scratch()) != 0) return false;
  }
  return true;
}
// b strictly between a and c on their line (given collinear).
bool between(const double* a, const double* b, const double* c) {
  for (int d = 0; d < 3; ++d)
    if (a[d] != c[d]) return (a[d] < b[d] && b[d] < c[d]) || (c[d] < b[d] && b[d] < a[d]);
  return false;
}
}  // namespace

Report check_hull3d(const double* p, std::int64_t n, const std::int32_t* t, std::int64_t nt,
                    std::int64_t max_pairs) {
  Report r;
  if (nt < 4) return r.fail("a closed hull surface needs at least 4 triangles"), r;
  for (std::int64_t f = 0; f < nt; ++f) {
    const std::int32_t* v = t + 3 * f;
    for (int j = 0; j < 3; ++j)
      if (v[j] < 0 || v[j] >= n)
        return r.fail(cell_name(3, f, t) + " refers to a missing point"), r;
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
      return r.fail(cell_name(3, f, t) + " repeats a vertex"), r;
    if (collinear3(at<3>(p, v[0]), at<3>(p, v[1]), at<3>(p, v[2])))
      return r.fail(cell_name(3, f, t) + " is degenerate (its vertices are collinear)"), r;
  }
  auto key = [](std::uint32_t u, std::uint32_t v) { return (std::uint64_t(u) << 32) | v; };
  std::unordered_map<std::uint64_t, std::pair<std::int64_t, std::int32_t>> edge;  // -> face, apex
  edge.reserve(std::size_t(nt) * 6);
  for (std::int64_t f = 0; f < nt; ++f)
    for (int j = 0; j < 3; ++j) {
      std::uint32_t u = t[3 * f + j], v = t[3 * f + (j + 1) % 3];
      if (!edge.emplace(key(u, v), std::make_pair(f, t[3 * f + (j + 2) % 3])).second)
        return r.fail("edge " + std::to_string(u) + "->" + std::to_string(v) +
                      " appears twice with the same direction (not an oriented 2-manifold)"),
               r;
    }
  std::unordered_map<std::int32_t, std::vector<std::int32_t>> nbrs;
  for (auto& e : edge) {
    std::uint32_t u = std::uint32_t(e.first >> 32), v = std::uint32_t(e.first);
    auto it = edge.find(key(v, u));
    if (it == edge.end())
      return r.fail("the surface is not closed: edge " + std::to_string(u) + "-" +
                    std::to_string(v) + " has only one triangle"),
             r;
    const std::int32_t* f = t + 3 * e.second.first;
    const std::int32_t far = it->second.second;
    if (pred::orient3d(at<3>(p, f[0]), at<3>(p, f[1]), at<3>(p, f[2]), at<3>(p, far), scratch()) >
        0)
      return r.fail("edge " + std::to_string(u) + "-" + std::to_string(v) + " is reflex: vertex " +
                    std::to_string(far) + " lies outside " + cell_name(3, e.second.first, t)),
             r;
    nbrs[std::int32_t(u)].push_back(std::int32_t(v));
  }
  const std::int64_t V = std::int64_t(nbrs.size()), E = std::int64_t(edge.size() / 2);
  if (V - E + nt != 2)
    return r.fail("the surface has Euler characteristic " + std::to_string(V - E + nt) + ", not 2"),
           r;
  // Connected: flood over edges.
  {
    std::unordered_set<std::int32_t> seen{nbrs.begin()->first};
    std::vector<std::int32_t> stack{nbrs.begin()->first};
    while (!stack.empty()) {
      std::int32_t u = stack.back();
      stack.pop_back();
      for (auto w : nbrs[u])
        if (seen.insert(w).second) stack.push_back(w);
    }
    if (std::int64_t(seen.size()) != V) return r.fail("the surface is not connected"), r;
  }
  // Extreme vertices: not inside a flat fan, not strictly inside a segment of two neighbours.
  for (auto& [v, nb] : nbrs) {
    const double* pv = at<3>(p, v);
    bool flat = true;
    const double *a = at<3>(p, nb[0]), *b = nullptr;
    for (std::size_t i = 1; i < nb.size() && !b; ++i)
      if (!collinear3(pv, a, at<3>(p, nb[i]))) b = at<3>(p, nb[i]);
    if (b)
      for (auto w : nb) flat = flat && pred::orient3d(pv, a, b, at<3>(p, w), scratch()) == 0;
    if (flat)
      return r.fail("hull vertex " + std::to_string(v) +
                    " is not extreme: it lies inside a flat face"),
             r;
    for (std::size_t i = 0; i < nb.size(); ++i)
      for (std::size_t j = i + 1; j < nb.size(); ++j) {
        const double *x = at<3>(p, nb[i]), *y = at<3>(p, nb[j]);
        if (collinear3(x, pv, y) && between(x, pv, y))
          return r.fail("hull vertex " + std::to_string(v) +
                        " is not extreme: it lies on the segment " + std::to_string(nb[i]) + "-" +
                        std::to_string(nb[j])),
                 r;
      }
  }
  // Containment, in parallel; a sample when the full check would be too long.
  std::int64_t step = 1;
  if (n > 0 && nt > 0 && n * nt > max_pairs) step = (n * nt + max_pairs - 1) / max_pairs;
  std::int64_t bad = -1;
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; i += step) {
    if (bad >= 0) continue;
    for (std::int64_t f = 0; f < nt; ++f) {
      const std::int32_t* v = t + 3 * f;
      if (pred::orient3d(at<3>(p, v[0]), at<3>(p, v[1]), at<3>(p, v[2]), at<3>(p, i), scratch()) >
          0) {
#pragma omp critical
        bad = bad < 0 ? i : std::min(bad, i);
        break;
      }
    }
  }
  if (bad >= 0) return r.fail("input point " + std::to_string(bad) + " lies outside the hull"), r;
  r.notes.push_back(std::to_string(nt) + " faces, " + std::to_string(V) +
                    " extreme vertices: valid convex hull");
  if (step > 1)
    r.notes.push_back("containment checked on every " + std::to_string(step) + "th point only");
  return r;
}

}  // namespace gpugeom::verify
