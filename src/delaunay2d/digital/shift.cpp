// The shifting phase (shift.hpp).
#include "delaunay2d/digital/shift.hpp"

#include <algorithm>
#include <array>
#include <unordered_map>

#include "delaunay2d/digital/ear_clip.hpp"
#include "delaunay2d/digital/hull_fill.hpp"
#include "gpugeom/predicates.hpp"

namespace gpugeom::del2d::digital {

namespace {

// Triangles with their half-edges' twins (sketch.hpp): a site's fan is walked across them, and
// a deletion replaces a fan, its new triangles paired with what was around it.
struct Mesh {
  std::vector<std::int32_t> tri, twin;  // 3 per triangle; half-edge 3t + k: vertex k to k + 1
  std::vector<char> alive;
  std::vector<std::int32_t> some;  // per point: one of its triangles, or -1

  std::int32_t add(std::int32_t a, std::int32_t b, std::int32_t c) {
    const std::int32_t t = std::int32_t(alive.size());
    tri.insert(tri.end(), {a, b, c});
    twin.insert(twin.end(), {-1, -1, -1});
    alive.push_back(1);
    some[std::size_t(a)] = some[std::size_t(b)] = some[std::size_t(c)] = t;
    return t;
  }
  void remove(std::int32_t t) {
    alive[std::size_t(t)] = 0;
    for (int k = 0; k < 3; ++k) {
      std::int32_t& e = twin[std::size_t(3 * t + k)];
      if (e >= 0) twin[std::size_t(e)] = -1;
      e = -1;
    }
  }
  int corner(std::int32_t t, std::int32_t v) const {
    return tri[std::size_t(3 * t)] == v ? 0 : (tri[std::size_t(3 * t + 1)] == v ? 1 : 2);
  }
  std::int32_t at(std::int32_t t, int k) const { return tri[std::size_t(3 * t + k % 3)]; }
};

// A vertex's fan, counter-clockwise: link[j], link[j + 1] span triangle tris[j]. An inner
// vertex's link is a cycle (link.size() == tris.size()); a boundary vertex's runs from the end
// of its outgoing boundary edge (link.front()) to the start of its incoming one (link.back()).
struct Fan {
  std::vector<std::int32_t> link, tris;
  bool boundary = false;
};

Fan fan_of(const Mesh& m, std::int32_t s) {
  Fan f;
  std::int32_t t = m.some[std::size_t(s)];
  int k = m.corner(t, s);
  // Clockwise to the first triangle (across s's outgoing edge), or all the way round.
  const std::int32_t t0 = t;
  for (;;) {
    const std::int32_t e = m.twin[std::size_t(3 * t + k)];
    if (e < 0) {
      f.boundary = true;
      break;
    }
    t = e / 3, k = m.corner(t, s);
    if (t == t0) break;
  }
  const std::int32_t first = t;
  f.link.push_back(m.at(t, k + 1));
  for (;;) {
    f.tris.push_back(t);
    const std::int32_t c = m.at(t, k + 2);
    if (f.boundary) f.link.push_back(c);
    const std::int32_t e = m.twin[std::size_t(3 * t + (k + 2) % 3)];  // across c -> s
    if (e < 0 || e / 3 == first) break;
    if (!f.boundary) f.link.push_back(c);
    t = e / 3, k = m.corner(t, s);
  }
  return f;
}

struct Positions {
  std::vector<double> xy;  // current positions: grid point or own coordinates
  Point2 at(std::int32_t i) const { return {xy[2 * std::size_t(i)], xy[2 * std::size_t(i) + 1]}; }
};

// Does the boundary turn left or go straight on at b (a -> b -> c)? (exact)
bool convex_turn(const Point2& a, const Point2& b, const Point2& c) {
  const int o = orient2d(a, b, c);
  if (o != 0) return o > 0;
  auto between = [](double u, double v, double w) { return (u < v && v < w) || (u > v && v > w); };
  return between(a.x, b.x, c.x) || (a.x == b.x && b.x == c.x && between(a.y, b.y, c.y));
}

// The hole an inner vertex leaves (its link, a simple counter-clockwise polygon), ear-clipped.
void fill_hole(Mesh& m, const Positions& P, const std::vector<std::int32_t>& link) {
  const auto left = clip_ears(
      link,
      [&](std::int32_t a, std::int32_t b, std::int32_t c) {
        return orient2d(P.at(a), P.at(b), P.at(c));
      },
      [&](std::int32_t a, std::int32_t b, std::int32_t c) { m.add(a, b, c); });
  if (left.size() >= 3) throw Error(ErrorCode::Internal, "shifting: a hole left unfilled");
}

// The chain a boundary vertex leaves (from the start of its incoming boundary edge to the end of
// its outgoing one, the new boundary's direction), made convex: each vertex where it turns right
// gets the triangle over it. The chain is angularly monotone around the deleted vertex, outside
// their hull, so this is the monotone-chain hull of those points, and each popped vertex's
// triangle lies between the chain and that hull.
std::int64_t fill_chain(Mesh& m, const Positions& P, const std::vector<std::int32_t>& chain) {
  std::vector<std::int32_t> st;
  std::int64_t added = 0;
  for (std::int32_t v : chain) {
    while (st.size() >= 2 && orient2d(P.at(st[st.size() - 2]), P.at(st.back()), P.at(v)) < 0) {
      m.add(st[st.size() - 2], v, st.back());
      ++added;
      st.pop_back();
    }
    st.push_back(v);
  }
  return added;
}

// Is the triangulation valid at P: every triangle counter-clockwise, V - E + F = 1, the boundary
// one cycle that turns left or goes straight everywhere and turns once (one lowest vertex)?
std::string check(const Mesh& m, const Positions& P) {
  std::unordered_map<std::int32_t, std::int32_t> next;
  std::int64_t faces = 0, half = 0;
  std::vector<char> used(m.some.size(), 0);
  for (std::int32_t t = 0; t < std::int32_t(m.alive.size()); ++t) {
    if (!m.alive[std::size_t(t)]) continue;
    ++faces;
    if (orient2d(P.at(m.at(t, 0)), P.at(m.at(t, 1)), P.at(m.at(t, 2))) <= 0)
      return "a triangle is not counter-clockwise";
    for (int k = 0; k < 3; ++k) {
      used[std::size_t(m.at(t, k))] = 1;
      ++half;
      if (m.twin[std::size_t(3 * t + k)] < 0 && !next.emplace(m.at(t, k), m.at(t, k + 1)).second)
        return "the boundary passes a vertex twice";
    }
  }
  if (!faces) return "no triangle";
  std::int64_t verts = 0;
  for (char u : used) verts += u;
  const std::int64_t edges = (half + std::int64_t(next.size())) / 2;
  if (verts - edges + faces != 1) return "not a disk";
  std::int32_t v = next.begin()->first;
  std::size_t steps = 0;
  int lowest = 0;
  auto below = [](const Point2& a, const Point2& b) {
    return a.y < b.y || (a.y == b.y && a.x < b.x);
  };
  std::int32_t prev = -1;
  for (const auto& [a, b] : next)
    if (b == v) prev = a;
  do {
    const std::int32_t w = next.at(v);
    if (!convex_turn(P.at(prev), P.at(v), P.at(w))) return "the boundary turns right";
    if (below(P.at(v), P.at(prev)) && below(P.at(v), P.at(w))) ++lowest;
    prev = v, v = w;
    if (++steps > next.size()) return "the boundary is not one cycle";
  } while (v != next.begin()->first);
  if (steps != next.size()) return "the boundary is not one cycle";
  if (lowest != 1) return "the boundary winds more than once";
  return {};
}

}  // namespace

Start shift_sketch(const double* xy, std::int64_t n, const Sketch& s) {
  Start out;
  if (!s.exact) {
    out.reason = "the grid points are not exact doubles";
    return out;
  }
  Mesh m;
  m.some.assign(std::size_t(n), -1);
  m.tri = s.triangles;
  m.twin = s.twin;
  m.alive.assign(m.tri.size() / 3, 1);
  for (std::size_t e = 0; e < m.tri.size(); ++e)
    m.some[std::size_t(m.tri[e])] = std::int32_t(e / 3);
  if (m.tri.empty()) {
    out.reason = "the sketch has no triangle";
    return out;
  }
  Positions P;
  P.xy.assign(2 * std::size_t(n), 0.0);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int32_t p = s.pixel[std::size_t(i)];
    P.xy[2 * std::size_t(i)] = s.ox + double(p % s.width) * s.h;
    P.xy[2 * std::size_t(i) + 1] = s.oy + double(p / s.width) * s.h;
  }
  // Alg. 4.4 in index order: each site moves where the triangulation stays valid with its
  // neighbours where they are.
  std::vector<std::int32_t> bad;
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int32_t v = std::int32_t(i);
    if (m.some[std::size_t(i)] < 0) continue;  // missing, or a site no triangle has
    const Point2 own{xy[2 * i], xy[2 * i + 1]};
    const Fan f = fan_of(m, v);
    bool good = true;
    const std::size_t k = f.link.size();
    for (std::size_t j = 0; good && j + (f.boundary ? 1 : 0) < k; ++j)
      good = orient2d(own, P.at(f.link[j]), P.at(f.link[(j + 1) % k])) > 0;
    if (good && f.boundary) {
      const std::int32_t q = f.link.front(), p = f.link.back();
      const std::int32_t pp = fan_of(m, p).link.back(), qq = fan_of(m, q).link.front();
      good = convex_turn(P.at(pp), P.at(p), own) && convex_turn(P.at(p), own, P.at(q)) &&
             convex_turn(own, P.at(q), P.at(qq));
    }
    if (good) {
      P.xy[2 * std::size_t(i)] = own.x, P.xy[2 * std::size_t(i) + 1] = own.y;
      ++out.shifted;
    } else {
      bad.push_back(v);
    }
  }
  // Alg. 4.5: the bad cases deleted (each at its grid point, the triangulation valid around it).
  // A point's hint: its pixel's site (itself for a site), then, once deleted, a neighbour.
  std::vector<std::int32_t> near(static_cast<std::size_t>(n));
  for (std::int64_t i = 0; i < n; ++i) near[std::size_t(i)] = s.site_of[std::size_t(i)];
  for (std::int32_t v : bad) {
    const Fan f = fan_of(m, v);
    near[std::size_t(v)] = f.link.front();
    // The half-edges around the fan, open once it goes: the new triangles pair with them.
    std::vector<std::int32_t> open;
    for (std::int32_t t : f.tris) {
      const int k = m.corner(t, v);
      const std::int32_t o = m.twin[std::size_t(3 * t + (k + 1) % 3)];  // across the link edge
      if (o >= 0) open.push_back(o);
    }
    for (std::int32_t t : f.tris) m.remove(t);
    m.some[std::size_t(v)] = -1;
    const std::int64_t first = std::int64_t(m.alive.size());
    if (!f.boundary) {
      fill_hole(m, P, f.link);
      ++out.bad_inner;
    } else {
      std::vector<std::int32_t> chain(f.link.rbegin(), f.link.rend());
      out.filled += fill_chain(m, P, chain);
      ++out.bad_boundary;
    }
    pair_new_half_edges(m.tri, m.twin, first, open);
    // The link's vertices keep a triangle of theirs (or none: they become missing points).
    for (std::int32_t o : open)
      for (int j = 0; j < 3; ++j) {
        std::int32_t& t = m.some[std::size_t(m.at(o / 3, j))];
        if (t < 0 || !m.alive[std::size_t(t)]) t = o / 3;
      }
    for (std::int32_t a : f.link) {
      std::int32_t& t = m.some[std::size_t(a)];
      if (t >= 0 && !m.alive[std::size_t(t)]) t = -1;
    }
  }
  out.reason = check(m, P);
  if (!out.reason.empty()) return out;
  // The live triangles, renumbered, with their twins.
  std::vector<std::int32_t> slot(m.alive.size(), -1);
  std::int32_t live = 0;
  for (std::size_t t = 0; t < m.alive.size(); ++t)
    if (m.alive[t]) slot[t] = live++;
  out.triangles.resize(3 * std::size_t(live));
  out.twin.resize(3 * std::size_t(live));
  for (std::size_t t = 0; t < m.alive.size(); ++t) {
    if (slot[t] < 0) continue;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::int32_t o = m.twin[3 * t + k];
      out.triangles[3 * std::size_t(slot[t]) + k] = m.tri[3 * t + k];
      out.twin[3 * std::size_t(slot[t]) + k] = o < 0 ? -1 : 3 * slot[std::size_t(o / 3)] + o % 3;
    }
  }
  for (std::int64_t i = 0; i < n; ++i) out.vertices += m.some[std::size_t(i)] >= 0;
  // Hints followed to a vertex of the start (a deleted neighbour's own hint, and so on).
  out.hint.assign(static_cast<std::size_t>(n), -1);
  for (std::int64_t i = 0; i < n; ++i) {
    if (m.some[std::size_t(i)] >= 0) continue;
    std::int32_t v = near[std::size_t(i)];
    for (int step = 0; step < 64 && v >= 0 && m.some[std::size_t(v)] < 0; ++step)
      v = v == near[std::size_t(v)] ? -1 : near[std::size_t(v)];
    out.hint[std::size_t(i)] = v >= 0 && m.some[std::size_t(v)] >= 0 ? v : -1;
  }
  out.valid = true;
  return out;
}

}  // namespace gpugeom::del2d::digital
