// Shared by the CPU and CUDA hull tests: inputs (distributions and degenerate sets) and the
// full validation of a result.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "../common/kept_operations.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/hull3d.hpp"
#include "verify.hpp"

namespace gg_hull3d {
using gpugeom::Point3;

struct Case {
  std::string name;
  std::vector<Point3> pts;
};

// Options that run on the CPU executor (the CPU tests' default).
inline gpugeom::Hull3dOptions cpu() {
  gpugeom::Hull3dOptions o;
  o.backend = gpugeom::Backend::Cpu;
  return o;
}

inline std::vector<Case> distribution_cases(const std::vector<std::int64_t>& sizes,
                                            std::uint64_t seed) {
  std::vector<Case> out;
  for (const auto& d : gpugeom::distributions3d())
    for (auto n : sizes) {
      if ((d == "grid" || d == "two_lines") && n < 100) continue;  // may be coplanar
      // Points on two segments take about one insertion round per point and facet (collinear
      // runs, docs/performance.md); above this size the case is a benchmark, not a test.
      if (d == "two_lines" && n > 20000) continue;
      out.push_back({d + "/" + std::to_string(n), gpugeom::generate3d(d, n, seed)});
    }
  return out;
}

// Exactly degenerate inputs: points on faces and edges, grids, copies, cospherical points,
// coordinates of very different magnitudes.
inline std::vector<Case> degenerate_cases() {
  std::vector<Case> out;
  std::mt19937_64 rng(7);
  for (int k : {1, 2, 3, 5, 8}) {  // full integer grids
    Case c{"grid" + std::to_string(k + 1), {}};
    for (int x = 0; x <= k; ++x)
      for (int y = 0; y <= k; ++y)
        for (int z = 0; z <= k; ++z) c.pts.push_back({double(x), double(y), double(z)});
    std::shuffle(c.pts.begin(), c.pts.end(), rng);
    out.push_back(c);
  }
  {
    // The first tetrahedron's third point is the one farthest from the line through the
    // lexicographic extremes A and B: here thousands of points on a cylinder around that line
    // are equally far but for rounding, so the choice hangs on how |(q - A) x (B - A)|^2 is
    // rounded. Executors that contracted it differently (FMA on the GPU only) picked different
    // points, and returned different arrays for the same hull.
    Case c{"cylinder_ties", {}};
    const double A[3] = {-10, -3, 1}, u[3] = {20, 13, 7};
    // two unit vectors orthogonal to u and to each other
    const double n0 = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    double e1[3] = {u[1], -u[0], 0}, e2[3];
    const double l1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1]);
    for (double& v : e1) v /= l1;
    e2[0] = (u[1] * e1[2] - u[2] * e1[1]) / n0;
    e2[1] = (u[2] * e1[0] - u[0] * e1[2]) / n0;
    e2[2] = (u[0] * e1[1] - u[1] * e1[0]) / n0;
    c.pts.push_back({A[0], A[1], A[2]});
    c.pts.push_back({A[0] + u[0], A[1] + u[1], A[2] + u[2]});
    std::uniform_real_distribution<double> t(0.2, 0.8), ang(0, 6.283185307179586);
    for (int i = 0; i < 4000; ++i) {
      const double s = t(rng), a = ang(rng), cs = std::cos(a), sn = std::sin(a);
      c.pts.push_back({A[0] + s * u[0] + cs * e1[0] + sn * e2[0],
                       A[1] + s * u[1] + cs * e1[1] + sn * e2[1],
                       A[2] + s * u[2] + cs * e1[2] + sn * e2[2]});
    }
    std::shuffle(c.pts.begin(), c.pts.end(), rng);
    out.push_back(c);
  }
  {  // integer points on the cube's faces only
    Case c{"cube_faces", {}};
    const int k = 9;
    for (int x = 0; x <= k; ++x)
      for (int y = 0; y <= k; ++y)
        for (int z = 0; z <= k; ++z)
          if (x == 0 || y == 0 || z == 0 || x == k || y == k || z == k)
            c.pts.push_back({double(x), double(y), double(z)});
    std::shuffle(c.pts.begin(), c.pts.end(), rng);
    out.push_back(c);
  }
  {  // a tetrahedron with integer points on its faces and edges, and some inside
    Case c{"tetra_faces", {}};
    const int k = 12;
    for (int x = 0; x <= k; ++x)
      for (int y = 0; x + y <= k; ++y)
        for (int z = 0; x + y + z <= k; ++z)
          if (x == 0 || y == 0 || z == 0 || x + y + z == k || (x + y + z) % 5 == 1)
            c.pts.push_back({double(x), double(y), double(z)});
    std::shuffle(c.pts.begin(), c.pts.end(), rng);
    out.push_back(c);
  }
  {  // an octahedron with points along its edges
    Case c{"octahedron_edges", {}};
    const int k = 16;
    const int ax[6][3] = {{k, 0, 0}, {-k, 0, 0}, {0, k, 0}, {0, -k, 0}, {0, 0, k}, {0, 0, -k}};
    for (int a = 0; a < 6; ++a)
      for (int b = a + 1; b < 6; ++b) {
        if (a / 2 == b / 2) continue;  // opposite vertices: not an edge
        for (int t = 0; t <= k; ++t)
          c.pts.push_back({double((ax[a][0] * (k - t) + ax[b][0] * t) / k),
                           double((ax[a][1] * (k - t) + ax[b][1] * t) / k),
                           double((ax[a][2] * (k - t) + ax[b][2] * t) / k)});
      }
    c.pts.push_back({0, 0, 0});
    std::shuffle(c.pts.begin(), c.pts.end(), rng);
    out.push_back(c);
  }
  {  // integer points on the sphere x^2 + y^2 + z^2 = 3 * 7^2 (exactly cospherical)
    Case c{"cospherical", {}};
    const int r2 = 147;
    for (int x = -12; x <= 12; ++x)
      for (int y = -12; y <= 12; ++y)
        for (int z = -12; z <= 12; ++z)
          if (x * x + y * y + z * z == r2) c.pts.push_back({double(x), double(y), double(z)});
    out.push_back(c);
  }
  {  // every point three times, in shuffled order, with -0 for some zeros
    Case c{"copies", {}};
    auto b = gpugeom::generate3d("ball", 500, 3);
    for (int r = 0; r < 3; ++r) c.pts.insert(c.pts.end(), b.begin(), b.end());
    c.pts.push_back({0.0, -0.0, 0.0});
    c.pts.push_back({-0.0, 0.0, -0.0});
    std::shuffle(c.pts.begin(), c.pts.end(), rng);
    out.push_back(c);
  }
  {  // a box's 8 corners repeated, with points inside its faces
    Case c{"box_copies", {}};
    for (int r = 0; r < 4; ++r)
      for (int m = 0; m < 8; ++m)
        c.pts.push_back({double(m & 1), double((m >> 1) & 1), double(m >> 2)});
    for (int i = 1; i < 8; ++i) c.pts.push_back({i / 8.0, 0.5, 1.0});
    std::shuffle(c.pts.begin(), c.pts.end(), rng);
    out.push_back(c);
  }
  {  // huge and tiny coordinates together
    Case c{"magnitudes", {}};
    for (auto p : gpugeom::generate3d("ball", 300, 5))
      c.pts.push_back({p.x * 1e40, p.y * 1e40, p.z * 1e40});
    for (auto p : gpugeom::generate3d("sphere", 300, 6))
      c.pts.push_back({p.x * 1e-30, p.y * 1e-30, p.z * 1e-30});
    c.pts.push_back({1e-40, -3e-41, 2e-42});
    out.push_back(c);
  }
  {  // a needle: almost collinear, but not
    Case c{"needle",
           {{0, 0, 0}, {1, 0, 0}, {0.5, 1e-12, 0}, {0.25, 0, 1e-12}, {0.75, -1e-13, -1e-13}}};
    out.push_back(c);
  }
  return out;
}

// The checker, plus the parts of the result the checker does not see: vertex list,
// neighbours, plane equations, and that no two vertices are copies of one point.
inline void expect_valid(const std::vector<Point3>& pts, const gpugeom::ConvexHull3d& h) {
  const double* p = &pts.data()->x;
  const std::int64_t n = std::int64_t(pts.size());
  const auto nt = h.num_facets;
  auto r = gpugeom::verify::check_hull3d(p, n, h.triangles.data(), nt, 1'000'000'000LL);
  ASSERT_TRUE(r.ok) << r.message;
  std::set<std::int32_t> vs(h.triangles.begin(), h.triangles.end());
  ASSERT_EQ(std::vector<std::int32_t>(vs.begin(), vs.end()), h.vertices);
  ASSERT_EQ(h.neighbors.size(), h.triangles.size());
  for (std::int64_t f = 0; f < nt; ++f)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t g = h.neighbors[3 * f + k];
      ASSERT_TRUE(g >= 0 && g < nt);
      const std::int32_t u = h.triangles[3 * f + (k + 1) % 3], v = h.triangles[3 * f + (k + 2) % 3];
      bool shares = false, back = false;
      for (int j = 0; j < 3; ++j) {
        shares = shares ||
                 (h.triangles[3 * g + (j + 1) % 3] == v && h.triangles[3 * g + (j + 2) % 3] == u);
        back = back || h.neighbors[3 * g + j] == f;
      }
      ASSERT_TRUE(shares && back) << "facet " << f << " neighbour " << k;
    }
  ASSERT_EQ(h.equations.size(), std::size_t(4 * nt));
  for (std::int64_t f = 0; f < nt; ++f) {
    const double* e = h.equations.data() + 4 * f;
    ASSERT_NEAR(e[0] * e[0] + e[1] * e[1] + e[2] * e[2], 1.0, 1e-12);
    double scale = 0;
    for (int k = 0; k < 3; ++k) {
      const Point3& q = pts[h.triangles[3 * f + k]];
      scale = std::max({scale, std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
    }
    for (int k = 0; k < 3; ++k) {
      const Point3& q = pts[h.triangles[3 * f + k]];
      ASSERT_LE(std::fabs(e[0] * q.x + e[1] * q.y + e[2] * q.z + e[3]), 1e-9 * scale);
    }
  }
  std::set<std::tuple<double, double, double>> seen;
  for (auto v : h.vertices)
    ASSERT_TRUE(seen.insert(std::make_tuple(pts[v].x + 0.0, pts[v].y + 0.0, pts[v].z + 0.0)).second)
        << "vertex " << v << " is a second copy of an extreme point";
}

// Facets as a canonical set (each rotated to start at its smallest index).
inline std::set<std::array<std::int32_t, 3>> facet_set(const std::vector<std::int32_t>& t) {
  std::set<std::array<std::int32_t, 3>> s;
  for (std::size_t f = 0; f < t.size() / 3; ++f) {
    std::array<std::int32_t, 3> a{t[3 * f], t[3 * f + 1], t[3 * f + 2]};
    std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
    s.insert(a);
  }
  return s;
}

// The facets in canonical order (the methods build the same hull in different slot orders).
inline std::vector<std::array<std::int32_t, 3>> facet_set(const gpugeom::ConvexHull3d& h) {
  return gpugeom::verify::canonical_triangles(h.triangles.data(), h.num_facets);
}

// The digital method's hull is valid and is the incremental method's, facet for facet, on the
// same executor. Returns the digital result.
inline gpugeom::ConvexHull3d expect_digital_same(const Case& c, gpugeom::Hull3dOptions o,
                                                 std::int64_t grid) {
  SCOPED_TRACE(c.name + " grid " + std::to_string(grid));
  o.method = gpugeom::Method::Incremental;
  o.grid = 0;
  const auto inc = gpugeom::convex_hull3d(c.pts, o);
  o.method = gpugeom::Method::Digital;
  o.grid = grid;
  const auto dig = gpugeom::convex_hull3d(c.pts, o);
  expect_valid(c.pts, dig);
  EXPECT_EQ(facet_set(dig), facet_set(inc));
  EXPECT_EQ(dig.vertices, inc.vertices);
  // Every point the last hull saw: the sketch's and those the depth test kept.
  const auto& k = dig.stats;
  if (!k.digital_fallback) EXPECT_EQ(k.hull_input, k.sketch_points + k.depth_kept);
  return dig;
}

// DynamicHull3d for gg_test::KeptOperations: the facets, and the extreme points, as a fresh hull's
// of the points left.
struct KeptHull {
  using Point = Point3;
  using Dyn = gpugeom::DynamicHull3d;
  using Result = gpugeom::ConvexHull3d;
  using Options = gpugeom::Hull3dOptions;
  static constexpr int kVerts = 3, kDim = 3;
  static Result fresh(const std::vector<Point>& p, const Options& o) {
    Options f;
    f.backend = o.backend;
    return gpugeom::convex_hull3d(p, f);
  }
  static Result current(const Dyn& d) { return d.hull(); }
  static void valid(const std::vector<Point>& p, const Result& h) { expect_valid(p, h); }
  static const std::int32_t* simplices(const Result& h) { return h.triangles.data(); }
  static const std::int32_t* neighbors(const Result& h) { return h.neighbors.data(); }
  static std::int64_t count(const Result& h) { return h.num_facets; }
  static void expect_same(const Result& got, const Result& fresh,
                          const std::vector<std::int32_t>& ids, std::size_t) {
    std::vector<std::int32_t> want;
    for (auto v : fresh.vertices) want.push_back(ids[std::size_t(v)]);
    EXPECT_EQ(std::vector<std::int32_t>(got.vertices.begin(), got.vertices.end()), want);
  }
  // (no vertex removed: the hull stayed)
  static bool local_removal(const gpugeom::Hull3dStats& st) { return st.removed_vertices == 0; }
  static bool enough_local(int local, int) { return local > 0; }
  static void shift(Point& p, double s, std::mt19937_64& rng) {
    std::normal_distribution<double> N(0, s);
    p.x += N(rng), p.y += N(rng), p.z += N(rng);
  }
};

}  // namespace gg_hull3d
