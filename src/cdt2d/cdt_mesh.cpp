// The host triangulation that takes constraints: segment recovery by flips, then Lawson's flips
// with the segments' edges fixed (cdt_mesh.hpp).
#include "cdt2d/cdt_mesh.hpp"

#include <cmath>
#include <deque>
#include <string>

#include "gpugeom/common.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::cdt {

CdtMesh::CdtMesh(const double* xy, std::int64_t n, std::vector<std::int32_t> tris,
                 std::vector<std::int32_t> nbrs)
    : xy_(xy),
      n_(n),
      tri_(std::move(tris)),
      nbr_(std::move(nbrs)),
      seg_(tri_.size(), -1),
      vt_(std::size_t(n), -1),
      scratch_(std::size_t(pred::kIncircleScratch + pred::kOrient2dScratch)) {
  for (std::size_t i = 0; i < tri_.size(); ++i) vt_[std::size_t(tri_[i])] = std::int32_t(i / 3);
}

int CdtMesh::orient(std::int32_t a, std::int32_t b, std::int32_t c) const {
  return pred::orient2d(p(a), p(b), p(c), const_cast<double*>(scratch_.data()));
}

bool CdtMesh::ahead(std::int32_t a, std::int32_t b, std::int32_t u, std::int32_t w) const {
  // Points of one line are ordered by the coordinate along which the line moves more (the
  // sign of a difference of doubles is exact).
  const double *pa = p(a), *pb = p(b), *pu = p(u), *pw = p(w);
  const int d = std::abs(pb[0] - pa[0]) >= std::abs(pb[1] - pa[1]) ? 0 : 1;
  const double sgn = pb[d] > pa[d] ? 1.0 : -1.0;
  return (pw[d] - pu[d]) * sgn > 0 && (pb[d] - pw[d]) * sgn >= 0;
}

CdtMesh::Edge CdtMesh::find_edge(std::int32_t u, std::int32_t v) const {
  // Around u counter-clockwise from one of its triangles, then clockwise if the hull stops it.
  const std::int32_t start = vt_[std::size_t(u)];
  for (int dir = 0; dir < 2; ++dir) {
    std::int32_t t = start;
    for (std::int64_t steps = 0; t >= 0 && steps <= n_; ++steps) {
      int i = 0;
      while (tri_[3 * std::size_t(t) + i] != u) ++i;
      const std::int32_t v1 = tri_[3 * std::size_t(t) + (i + 1) % 3];
      if (v1 == v) return {t, std::int32_t((i + 2) % 3)};
      // counter-clockwise: across (u, v2), opposite v1; clockwise: across (u, v1), opposite v2
      t = nbr_[3 * std::size_t(t) + (dir == 0 ? (i + 1) % 3 : (i + 2) % 3)];
      if (t == start) break;
    }
    if (t == start) break;  // went all the way round: u is inside the hull
  }
  return {-1, -1};
}

void CdtMesh::mark(std::int32_t u, std::int32_t v, std::int32_t id) {
  for (Edge e : {find_edge(u, v), find_edge(v, u)})
    if (e.t >= 0 && seg_[3 * std::size_t(e.t) + e.k] < 0) seg_[3 * std::size_t(e.t) + e.k] = id;
}

CdtMesh::Edge CdtMesh::flip(Edge e) {
  // t = (a, b, c) with the edge b-c opposite a; o = (d, c, b) across it. After: t = (a, b, d),
  // o = (d, c, a), sharing a-d.
  const std::size_t t = std::size_t(e.t), k = std::size_t(e.k);
  const std::int32_t os = nbr_[3 * t + k];
  const std::size_t o = std::size_t(os);
  std::size_t ko = 0;
  while (nbr_[3 * o + ko] != e.t) ++ko;
  const std::int32_t a = tri_[3 * t + k], b = tri_[3 * t + (k + 1) % 3],
                     c = tri_[3 * t + (k + 2) % 3], d = tri_[3 * o + ko];
  const std::int32_t n_ab = nbr_[3 * t + (k + 2) % 3], s_ab = seg_[3 * t + (k + 2) % 3];
  const std::int32_t n_ca = nbr_[3 * t + (k + 1) % 3], s_ca = seg_[3 * t + (k + 1) % 3];
  const std::int32_t n_dc = nbr_[3 * o + (ko + 2) % 3], s_dc = seg_[3 * o + (ko + 2) % 3];
  const std::int32_t n_bd = nbr_[3 * o + (ko + 1) % 3], s_bd = seg_[3 * o + (ko + 1) % 3];
  auto set = [&](std::size_t x, std::int32_t v0, std::int32_t v1, std::int32_t v2, std::int32_t m0,
                 std::int32_t m1, std::int32_t m2, std::int32_t g0, std::int32_t g1,
                 std::int32_t g2) {
    tri_[3 * x] = v0, tri_[3 * x + 1] = v1, tri_[3 * x + 2] = v2;
    nbr_[3 * x] = m0, nbr_[3 * x + 1] = m1, nbr_[3 * x + 2] = m2;
    seg_[3 * x] = g0, seg_[3 * x + 1] = g1, seg_[3 * x + 2] = g2;
  };
  set(t, a, b, d, n_bd, os, n_ab, s_bd, -1, s_ab);
  set(o, d, c, a, n_ca, e.t, n_dc, s_ca, -1, s_dc);
  auto repoint = [&](std::int32_t x, std::int32_t from, std::int32_t to) {
    if (x < 0) return;
    for (int j = 0; j < 3; ++j)
      if (nbr_[3 * std::size_t(x) + j] == from) nbr_[3 * std::size_t(x) + j] = to;
  };
  repoint(n_bd, os, e.t);
  repoint(n_ca, e.t, os);
  vt_[std::size_t(a)] = vt_[std::size_t(b)] = vt_[std::size_t(d)] = e.t;
  vt_[std::size_t(c)] = os;
  return {e.t, 1};
}

std::int32_t CdtMesh::walk(std::int32_t a, std::int32_t b, std::int32_t u, std::int32_t id,
                           std::vector<std::pair<std::int32_t, std::int32_t>>& crossed) {
  auto crossing = [&](std::size_t t, int k) {
    const std::int32_t s = seg_[3 * t + k];
    if (s >= 0)
      throw Error(ErrorCode::InvalidInput,
                  "segments " + std::to_string(s) + " and " + std::to_string(id) +
                      " cross each other at a point that is not an input point: split them "
                      "there (add the crossing as a point and end both segments at it)");
  };
  // The triangle at u whose wedge holds the direction to b, or an edge from u along it.
  const std::int32_t start = vt_[std::size_t(u)];
  std::int32_t t = -1, iu = 0;
  for (int dir = 0; dir < 2 && t < 0; ++dir) {
    std::int32_t s = start;
    for (std::int64_t steps = 0; s >= 0 && steps <= n_; ++steps) {
      int i = 0;
      while (tri_[3 * std::size_t(s) + i] != u) ++i;
      const std::int32_t v1 = tri_[3 * std::size_t(s) + (i + 1) % 3],
                         v2 = tri_[3 * std::size_t(s) + (i + 2) % 3];
      for (std::int32_t v : {v1, v2})
        if (v == b || (orient(a, b, v) == 0 && ahead(a, b, u, v))) return v;
      if (orient(u, v1, b) > 0 && orient(u, v2, b) < 0) {
        t = s, iu = i;
        break;
      }
      s = nbr_[3 * std::size_t(s) + (dir == 0 ? (i + 1) % 3 : (i + 2) % 3)];
      if (s == start) break;
    }
  }
  if (t < 0)
    throw Error(ErrorCode::Internal, "cdt2d: no triangle at vertex " + std::to_string(u) +
                                         " faces segment " + std::to_string(id));
  // Across the triangles it crosses: each crossed edge as (left of a->b, right of it).
  std::int32_t l = tri_[3 * std::size_t(t) + (iu + 2) % 3],
               r = tri_[3 * std::size_t(t) + (iu + 1) % 3];
  int k = iu;
  crossing(std::size_t(t), k);
  crossed.push_back({l, r});
  for (std::int64_t steps = 0; steps <= 3 * std::int64_t(tri_.size()); ++steps) {
    const std::int32_t o = nbr_[3 * std::size_t(t) + k];
    if (o < 0) break;
    int kw = 0;
    while (tri_[3 * std::size_t(o) + kw] == l || tri_[3 * std::size_t(o) + kw] == r) ++kw;
    const std::int32_t w = tri_[3 * std::size_t(o) + kw];
    if (w == b) return b;
    const int side = orient(a, b, w);
    if (side == 0) return w;  // the segment runs through w: the piece ends there
    // It leaves o by the edge (w, r) if w is on the left, else by (l, w).
    const std::int32_t opposite = side > 0 ? l : r;
    k = 0;
    while (tri_[3 * std::size_t(o) + k] != opposite) ++k;
    t = o;
    if (side > 0)
      l = w;
    else
      r = w;
    crossing(std::size_t(t), k);
    crossed.push_back({l, r});
  }
  throw Error(ErrorCode::Internal,
              "cdt2d: segment " + std::to_string(id) + " left the triangulation");
}

bool CdtMesh::insert_segment(std::int32_t a, std::int32_t b, std::int32_t id) {
  bool flipped = false;
  std::vector<std::pair<std::int32_t, std::int32_t>> crossed;
  for (std::int32_t u = a; u != b;) {
    crossed.clear();
    const std::int32_t w = walk(a, b, u, id, crossed);
    // Sloan's recovery: flip a crossed edge whose quadrilateral is convex; the new edge goes
    // back to the queue if it still crosses the piece u-w. Some crossed edge is always
    // flippable, so the queue empties.
    std::deque<std::pair<std::int32_t, std::int32_t>> queue(crossed.begin(), crossed.end());
    std::int64_t idle = 0;
    while (!queue.empty()) {
      const auto [x, y] = queue.front();
      queue.pop_front();
      Edge e = find_edge(x, y);
      if (e.t < 0) e = find_edge(y, x);
      if (e.t < 0 || nbr_[3 * std::size_t(e.t) + std::size_t(e.k)] < 0)
        throw Error(ErrorCode::Internal,
                    "cdt2d: a crossed edge of segment " + std::to_string(id) + " is gone");
      const std::size_t t = std::size_t(e.t), k = std::size_t(e.k);
      const std::int32_t o = nbr_[3 * t + k];
      std::size_t ko = 0;
      while (nbr_[3 * std::size_t(o) + ko] != e.t) ++ko;
      const std::int32_t ap = tri_[3 * t + k], bp = tri_[3 * t + (k + 1) % 3],
                         cp = tri_[3 * t + (k + 2) % 3], dp = tri_[3 * std::size_t(o) + ko];
      if (orient(ap, bp, dp) <= 0 || orient(dp, cp, ap) <= 0) {  // not strictly convex: later
        queue.push_back({x, y});
        if (++idle > std::int64_t(queue.size()) + 1)
          throw Error(ErrorCode::Internal, "cdt2d: no crossed edge of segment " +
                                               std::to_string(id) + " can be flipped");
        continue;
      }
      idle = 0;
      flip(e);
      ++recovery_flips_;
      // The quadrilateral's edges are the only ones whose triangles changed: they alone may
      // have stopped being locally Delaunay.
      for (const auto& q : {std::pair{ap, bp}, {bp, dp}, {dp, cp}, {cp, ap}, {ap, dp}})
        touched_.push_back(q);
      flipped = true;
      if (orient(u, w, ap) * orient(u, w, dp) < 0) queue.push_back({ap, dp});
    }
    mark(u, w, id);
    ++pieces_;
    u = w;
  }
  return flipped;
}

void CdtMesh::restore_delaunay() {
  // The edges of the quadrilaterals the recovery flipped (every other edge still has the two
  // triangles it had in the Delaunay triangulation), then those of each quadrilateral flipped
  // here.
  std::vector<std::pair<std::int32_t, std::int32_t>> stack = std::move(touched_);
  touched_.clear();
  double* s = scratch_.data();
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    const Edge e = find_edge(x, y);
    if (e.t < 0) continue;  // flipped away, or a hull edge seen from outside
    const std::size_t t = std::size_t(e.t), k = std::size_t(e.k);
    const std::int32_t o = nbr_[3 * t + k];
    if (o < 0 || seg_[3 * t + k] >= 0) continue;  // the hull, or a segment's edge
    std::size_t ko = 0;
    while (nbr_[3 * std::size_t(o) + ko] != e.t) ++ko;
    const std::int32_t ap = tri_[3 * t + k], bp = tri_[3 * t + (k + 1) % 3],
                       cp = tri_[3 * t + (k + 2) % 3], dp = tri_[3 * std::size_t(o) + ko];
    if (pred::incircle(p(ap), p(bp), p(cp), p(dp), s) <= 0) continue;
    // d inside the circle of (a, b, c) makes the quadrilateral strictly convex.
    flip(e);
    ++delaunay_flips_;
    stack.push_back({ap, bp});
    stack.push_back({bp, dp});
    stack.push_back({dp, cp});
    stack.push_back({cp, ap});
  }
}

}  // namespace gpugeom::cdt
