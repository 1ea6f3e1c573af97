// Inputs for the constrained Delaunay tests: random planar straight-line graphs (segments that
// do not cross, some through other points), degenerate layouts, and the checks every result
// must pass.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "gpugeom/cdt2d.hpp"
#include "predicates/predicates.hpp"
#include "verify.hpp"

namespace gg_cdt {

struct Pslg {
  std::string name;
  std::vector<double> xy;
  std::vector<std::int32_t> segs;
};

inline int orient(const std::vector<double>& p, std::int32_t a, std::int32_t b, std::int32_t c) {
  static thread_local std::vector<double> s(gpugeom::pred::kOrient2dScratch);
  return gpugeom::pred::orient2d(&p[2 * a], &p[2 * b], &p[2 * c], s.data());
}
// Do segments (a, b) and (c, d) meet at a point inside both that is not an input point? Exact.
inline bool proper_cross(const std::vector<double>& p, std::int32_t a, std::int32_t b,
                         std::int32_t c, std::int32_t d) {
  // (Collinear overlapping segments are fine: the library takes them as one chain.)
  return orient(p, a, b, c) * orient(p, a, b, d) < 0 && orient(p, c, d, a) * orient(p, c, d, b) < 0;
}

// Random segments between near points, kept when they cross no segment kept before: each from a
// random point to the nearest of `partners` random others (fewer: longer segments, crossing more
// triangles).
inline Pslg random_pslg(std::int64_t n, std::int64_t tries, unsigned seed, int partners = 8) {
  Pslg g{"random pslg " + std::to_string(n) + " seed " + std::to_string(seed) + " partners " +
             std::to_string(partners),
         {},
         {}};
  std::mt19937_64 r(seed);
  std::uniform_real_distribution<double> U(0, 1);
  for (std::int64_t i = 0; i < n; ++i) g.xy.insert(g.xy.end(), {U(r), U(r)});
  for (std::int64_t k = 0; k < tries; ++k) {
    const std::int32_t a = std::int32_t(r() % n);
    // a partner among a few random points: the nearest, so segments stay short
    std::int32_t b = -1;
    double best = 1e300;
    for (int j = 0; j < partners; ++j) {
      const std::int32_t c = std::int32_t(r() % n);
      const double dx = g.xy[2 * c] - g.xy[2 * a], dy = g.xy[2 * c + 1] - g.xy[2 * a + 1];
      if (c != a && dx * dx + dy * dy < best) best = dx * dx + dy * dy, b = c;
    }
    if (b < 0) continue;
    bool ok = true;
    for (std::size_t s = 0; s < g.segs.size() && ok; s += 2)
      ok = !proper_cross(g.xy, a, b, g.segs[s], g.segs[s + 1]);
    if (ok) g.segs.insert(g.segs.end(), {a, b});
  }
  return g;
}

// Integer grid points (many cocircular) with segments along rows, diagonals and knight moves
// that cross nothing, some through grid points.
inline Pslg grid_pslg(int side) {
  Pslg g{"grid " + std::to_string(side), {}, {}};
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) g.xy.insert(g.xy.end(), {double(x), double(y)});
  auto id = [&](int x, int y) { return std::int32_t(y * side + x); };
  std::vector<std::int32_t> cand{id(0, 0),        id(side - 1, side - 1),  // the diagonal
                                 id(0, 1),        id(side - 1, 1),         // a row
                                 id(1, 3),        id(3, 4),
                                 id(5, 2),        id(7, 3),  // knight moves
                                 id(side - 1, 0), id(side - 3, 5)};
  for (std::size_t s = 0; s < cand.size(); s += 2) {
    bool ok = true;
    for (std::size_t t = 0; t < g.segs.size() && ok; t += 2)
      ok = !proper_cross(g.xy, cand[s], cand[s + 1], g.segs[t], g.segs[t + 1]);
    if (ok) g.segs.insert(g.segs.end(), {cand[s], cand[s + 1]});
  }
  return g;
}

// A thin polygon: two long rows of collinear points 1e-3 apart, its boundary as segments, and
// a segment along each whole row (through every point of it).
inline Pslg thin_polygon(int m) {
  Pslg g{"thin polygon " + std::to_string(m), {}, {}};
  for (int i = 0; i < m; ++i) g.xy.insert(g.xy.end(), {double(i), 0.0});
  for (int i = 0; i < m; ++i) g.xy.insert(g.xy.end(), {double(i), 1e-3});
  for (int i = 0; i + 1 < m; ++i) g.segs.insert(g.segs.end(), {i, i + 1, m + i + 1, m + i});
  g.segs.insert(g.segs.end(), {m - 1, 2 * m - 1, m, 0});
  g.segs.insert(g.segs.end(), {0, m - 1, m, 2 * m - 1});  // whole rows again (repeats pieces)
  g.segs.insert(g.segs.end(), {0, 2 * m - 1});            // the long diagonal
  return g;
}

// Contour lines: closed polylines around a centre (wavy rings of many points, every edge a
// segment), with points scattered between them, as terrain contours are.
inline Pslg contour_pslg(int rings, int per_ring, std::int64_t scattered, unsigned seed) {
  Pslg g{"contours " + std::to_string(rings) + "x" + std::to_string(per_ring), {}, {}};
  std::mt19937_64 r(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int k = 0; k < rings; ++k) {
    const double radius = 0.1 + 0.85 * (k + 1) / rings;
    const std::int32_t first = std::int32_t(g.xy.size() / 2);
    for (int i = 0; i < per_ring; ++i) {
      const double a = 2 * 3.141592653589793 * i / per_ring;
      const double rr = radius * (1 + 0.3 / rings * std::sin(5 * a + k));  // rings never touch
      g.xy.insert(g.xy.end(), {rr * std::cos(a), rr * std::sin(a)});
      g.segs.insert(g.segs.end(), {first + i, first + (i + 1) % per_ring});
    }
  }
  for (std::int64_t i = 0; i < scattered; ++i) g.xy.insert(g.xy.end(), {U(r), U(r)});
  return g;
}

// A coastline-like closed polyline of m vertices (a star-shaped outline with detail at many
// scales and random jitter, so it never crosses itself), every edge a segment, and m / 10
// points scattered around it.
inline Pslg coastline_pslg(std::int64_t m, unsigned seed) {
  Pslg g{"coastline " + std::to_string(m), {}, {}};
  std::mt19937_64 r(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  const double pi = 3.141592653589793;
  for (std::int64_t i = 0; i < m; ++i) {
    const double a = 2 * pi * double(i) / double(m);
    const double rr = 1 + 0.25 * std::sin(7 * a) + 0.1 * std::sin(53 * a + 1) +
                      0.03 * std::sin(911 * a + 2) + 0.004 * U(r);
    g.xy.insert(g.xy.end(), {rr * std::cos(a), rr * std::sin(a)});
    g.segs.insert(g.segs.end(), {std::int32_t(i), std::int32_t((i + 1) % m)});
  }
  for (std::int64_t i = 0; i < m / 10; ++i) g.xy.insert(g.xy.end(), {1.5 * U(r), 1.5 * U(r)});
  return g;
}

// Points on a circle (all cocircular) with a star polygon of chords that do not cross, and
// points inside.
inline Pslg circle_pslg(int m, unsigned seed) {
  Pslg g{"circle " + std::to_string(m), {}, {}};
  for (int i = 0; i < m; ++i) {
    const double a = 2 * 3.141592653589793 * i / m;
    g.xy.insert(g.xy.end(), {std::cos(a), std::sin(a)});
  }
  std::mt19937 r(seed);
  std::uniform_real_distribution<double> U(-0.5, 0.5);
  for (int i = 0; i < m; ++i) g.xy.insert(g.xy.end(), {U(r), U(r)});
  for (int i = 0; i + 2 < m; i += 2) g.segs.insert(g.segs.end(), {i, i + 2});  // chords
  g.segs.insert(g.segs.end(), {0, m / 2});  // a diameter: m / 2 even, so it crosses no chord
  return g;
}

// Random segments that may cross each other (no filter), long and short.
inline Pslg crossing_pslg(std::int64_t n, std::int64_t m, unsigned seed) {
  Pslg g{"crossing pslg " + std::to_string(n) + "/" + std::to_string(m) + " seed " +
             std::to_string(seed),
         {},
         {}};
  std::mt19937_64 r(seed);
  std::uniform_real_distribution<double> U(0, 1);
  for (std::int64_t i = 0; i < n; ++i) g.xy.insert(g.xy.end(), {U(r), U(r)});
  for (std::int64_t k = 0; k < m; ++k)
    g.segs.insert(g.segs.end(), {std::int32_t(r() % n), std::int32_t(r() % n)});
  return g;
}

// The checks a result of Crossings::Split passes: the whole point set (input and new points) is
// constrained-Delaunay triangulated with the marked edges as its segments (exact checker), and
// the edges marked with each input segment form one path from its first end to its last, through
// input points exactly on it and new points within rounding of it (a new point is never more
// than a few units in the last place from both segments that made it).
inline void expect_split_cdt(const Pslg& g, const gpugeom::ConstrainedTriangulation2d& r) {
  const std::int64_t n = std::int64_t(g.xy.size() / 2);
  std::vector<double> xy = g.xy;
  xy.insert(xy.end(), r.new_points.begin(), r.new_points.end());
  const std::int64_t np = std::int64_t(xy.size() / 2);
  ASSERT_EQ(std::int64_t(r.duplicate_of.size()), np) << g.name;
  ASSERT_EQ(r.new_point_segments.size(), r.new_points.size()) << g.name;
  std::vector<std::int32_t> marked;
  std::vector<std::vector<std::int32_t>> edges_of(g.segs.size() / 2);
  for (std::size_t i = 0; i < r.segment_of.size(); ++i) {
    const std::int32_t s = r.segment_of[i];
    const std::int32_t u = r.triangles[i - i % 3 + (i % 3 + 1) % 3],
                       v = r.triangles[i - i % 3 + (i % 3 + 2) % 3];
    if (s < 0 || (r.neighbors[i] >= 0 && u > v)) continue;  // each marked edge once
    marked.insert(marked.end(), {u, v});
    edges_of[std::size_t(s)].insert(edges_of[std::size_t(s)].end(), {u, v});
  }
  auto rep = gpugeom::verify::check_constrained_delaunay2d(
      xy.data(), np, r.triangles.data(), r.num_triangles, marked.data(),
      std::int64_t(marked.size() / 2), r.duplicate_of.data());
  ASSERT_TRUE(rep.ok) << g.name << ": " << rep.message;
  for (std::size_t s = 0; s < g.segs.size() / 2; ++s) {
    std::int32_t a = g.segs[2 * s], b = g.segs[2 * s + 1];
    if (r.duplicate_of[a] >= 0) a = r.duplicate_of[a];
    if (r.duplicate_of[b] >= 0) b = r.duplicate_of[b];
    const auto& e = edges_of[s];
    if (a == b) {
      EXPECT_TRUE(e.empty()) << g.name << ": zero-length segment " << s << " marked";
      continue;
    }
    // (A repeated segment's edges carry the first one's mark: check the first of each.)
    bool first = true;
    for (std::size_t t = 0; t < s && first; ++t) {
      std::int32_t c = g.segs[2 * t], d = g.segs[2 * t + 1];
      if (r.duplicate_of[c] >= 0) c = r.duplicate_of[c];
      if (r.duplicate_of[d] >= 0) d = r.duplicate_of[d];
      first = !((c == a && d == b) || (c == b && d == a));
    }
    if (!first) continue;
    // Walk the path from a: every vertex has degree 2 in it but the ends.
    std::map<std::int32_t, std::vector<std::int32_t>> nb;
    for (std::size_t k = 0; k < e.size(); k += 2)
      nb[e[k]].push_back(e[k + 1]), nb[e[k + 1]].push_back(e[k]);
    std::int32_t at = a, prev = -1;
    std::size_t steps = 0;
    const double *pa = &xy[2 * std::size_t(a)], *pb = &xy[2 * std::size_t(b)];
    const double len = std::hypot(pb[0] - pa[0], pb[1] - pa[1]);
    while (at != b && steps <= e.size()) {
      const auto& o = nb[at];
      std::int32_t next = -1;
      for (std::int32_t w : o)
        if (w != prev) next = w;
      ASSERT_TRUE(next >= 0 && o.size() <= 2 && (at == a ? o.size() == 1 : o.size() == 2))
          << g.name << ": segment " << s << " is no path at vertex " << at;
      prev = at, at = next, ++steps;
      if (at == b) break;
      const double* q = &xy[2 * std::size_t(at)];
      const double dist =
          std::abs((pb[0] - pa[0]) * (q[1] - pa[1]) - (pb[1] - pa[1]) * (q[0] - pa[0])) / len;
      if (at < n)
        EXPECT_EQ(orient(xy, a, b, at), 0)
            << g.name << ": input point " << at << " on segment " << s << "'s path is off it";
      else
        EXPECT_LT(dist, 1e-12 * (1 + len))
            << g.name << ": new point " << at << " far from segment " << s;
    }
    EXPECT_EQ(at, b) << g.name << ": segment " << s << "'s path does not reach its end";
    EXPECT_EQ(steps, e.size() / 2) << g.name << ": segment " << s << " marks edges off its path";
  }
}

// The checks every result passes: the exact checker on the triangles and the segments given
// (after duplicates and drops), and every marked edge lies on the segment it names.
inline void expect_cdt(const Pslg& g, const gpugeom::ConstrainedTriangulation2d& r) {
  const std::int64_t n = std::int64_t(g.xy.size() / 2);
  std::vector<std::int32_t> segs;  // the segments as the triangulation sees them
  for (std::size_t s = 0; s < g.segs.size(); s += 2) {
    std::int32_t a = g.segs[s], b = g.segs[s + 1];
    if (r.duplicate_of[a] >= 0) a = r.duplicate_of[a];
    if (r.duplicate_of[b] >= 0) b = r.duplicate_of[b];
    if (a != b) segs.insert(segs.end(), {a, b});
  }
  auto rep = gpugeom::verify::check_constrained_delaunay2d(
      g.xy.data(), n, r.triangles.data(), r.num_triangles, segs.data(),
      std::int64_t(segs.size() / 2), r.duplicate_of.data());
  ASSERT_TRUE(rep.ok) << g.name << ": " << rep.message;
  for (std::size_t i = 0; i < r.segment_of.size(); ++i) {
    const std::int32_t s = r.segment_of[i];
    if (s < 0) continue;
    const std::int32_t u = r.triangles[i - i % 3 + (i % 3 + 1) % 3],
                       v = r.triangles[i - i % 3 + (i % 3 + 2) % 3];
    std::int32_t a = g.segs[2 * s], b = g.segs[2 * s + 1];
    if (r.duplicate_of[a] >= 0) a = r.duplicate_of[a];
    if (r.duplicate_of[b] >= 0) b = r.duplicate_of[b];
    ASSERT_TRUE(orient(g.xy, a, b, u) == 0 && orient(g.xy, a, b, v) == 0)
        << g.name << ": edge " << u << "-" << v << " is marked with segment " << s
        << " but does not lie on it";
  }
}

}  // namespace gg_cdt
