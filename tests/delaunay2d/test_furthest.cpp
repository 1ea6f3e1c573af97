// The furthest-site Delaunay triangulation (issue 49), judged by the exact predicates: every
// triangle counter-clockwise with every point inside or on its circumcircle, the triangles
// tiling the hull of the extreme points (each interior edge shared by two, the boundary the hull),
// on general, cocircular and duplicated input; its Voronoi diagram's rays pointing into the hull.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/predicates.hpp"
#include "gpugeom/removed.hpp"

using namespace gpugeom;

namespace {

void expect_furthest(const std::vector<Point2>& p) {
  const std::int64_t n = std::int64_t(p.size());
  Delaunay2dOptions o;
  o.backend = Backend::Cpu;
  const Triangulation2d t = furthest_site_delaunay2d(&p[0].x, n, o);
  const Triangulation2d d = delaunay2d(&p[0].x, n, o);
  const HostVector<std::int32_t> hull =
      convex_hull2d_vertices(&p[0].x, n, d.triangles.data(), d.neighbors.data(), d.num_triangles);
  const std::int64_t nt = t.num_triangles;
  ASSERT_EQ(nt, std::int64_t(hull.size()) - 2);  // (a triangulated convex polygon)
  std::set<std::int32_t> verts;
  std::map<std::pair<int, int>, int> edges;
  for (std::int64_t k = 0; k < nt; ++k) {
    const std::int32_t* v = &t.triangles[3 * k];
    ASSERT_GT(orient2d(p[v[0]], p[v[1]], p[v[2]]), 0) << k;
    for (std::int64_t i = 0; i < n; ++i)
      ASSERT_GE(incircle(p[v[0]], p[v[1]], p[v[2]], p[i]), 0) << "triangle " << k << " point " << i;
    for (int j = 0; j < 3; ++j) {
      verts.insert(v[j]);
      ++edges[{v[(j + 1) % 3], v[(j + 2) % 3]}];
      const std::int32_t o = t.neighbors[3 * k + j];
      if (o < 0) continue;  // (a boundary edge: checked against the hull below)
      bool shares = false;  // (the neighbour across edge a -> b holds b -> a)
      const std::int32_t a = v[(j + 1) % 3], b = v[(j + 2) % 3];
      for (int m = 0; m < 3; ++m)
        shares |= t.triangles[3 * o + m] == b && t.triangles[3 * o + (m + 1) % 3] == a;
      EXPECT_TRUE(shares) << "triangle " << k << " edge " << j;
    }
  }
  EXPECT_EQ(verts, std::set<std::int32_t>(hull.begin(), hull.end()));
  for (std::size_t k = 0; k < hull.size(); ++k) {  // (the boundary is the hull, once)
    const int a = hull[k], b = hull[(k + 1) % hull.size()];
    EXPECT_EQ(edges.count({a, b}), 1u);
    EXPECT_EQ(edges.count({b, a}), 0u);
  }
  for (std::int64_t i = 0; i < n; ++i) {
    const bool vertex = verts.count(std::int32_t(i)) > 0;
    const std::int32_t dup = t.duplicate_of[i];
    if (vertex) EXPECT_EQ(dup, -1);
    if (!vertex) EXPECT_TRUE(dup == kRemovedPoint || (dup >= 0 && verts.count(dup))) << i;
  }
  // the diagram: one ridge per edge, the unbounded ones on the hull edges, their
  // ridge_directions along the hull's outward normal (the furthest-site rays run the other way,
  // into the hull, as the Python layer gives them)
  const Voronoi2d v = voronoi2d(&p[0].x, n, t);
  double cx = 0, cy = 0;
  for (std::int32_t h : hull)
    cx += p[h].x / double(hull.size()), cy += p[h].y / double(hull.size());
  int rays = 0;
  for (std::size_t r = 0; r < v.ridge_points.size() / 2; ++r) {
    if (v.ridge_vertices[2 * r] >= 0 && v.ridge_vertices[2 * r + 1] >= 0) continue;
    ++rays;
    const Point2 a = p[v.ridge_points[2 * r]], b = p[v.ridge_points[2 * r + 1]];
    double nx = b.y - a.y, ny = a.x - b.x;  // (a normal of the edge, turned away from inside)
    if (nx * ((a.x + b.x) / 2 - cx) + ny * ((a.y + b.y) / 2 - cy) < 0) nx = -nx, ny = -ny;
    EXPECT_GT(v.ridge_directions[2 * r] * nx + v.ridge_directions[2 * r + 1] * ny, 0) << r;
  }
  EXPECT_EQ(rays, std::int64_t(hull.size()));
}

TEST(FurthestSite2d, ExactOnGeneralCocircularAndCopies) {
  std::mt19937_64 g(4);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Point2> p;
  for (int i = 0; i < 2000; ++i) p.push_back({u(g), u(g)});
  expect_furthest(p);
  // points on a circle exactly (integer points on x^2 + y^2 = 25^2) with the centre and a copy
  std::vector<Point2> c;
  for (int x = -25; x <= 25; ++x)
    for (int y = -25; y <= 25; ++y)
      if (x * x + y * y == 625) c.push_back({double(x), double(y)});
  c.push_back({0, 0});
  c.push_back(c[3]);
  expect_furthest(c);
  // a square grid: only the four corners are extreme (cocircular)
  std::vector<Point2> s;
  for (int x = 0; x < 5; ++x)
    for (int y = 0; y < 5; ++y) s.push_back({double(x), double(y)});
  expect_furthest(s);
}

TEST(FurthestSite2d, CollinearPointsAreRefused) {
  const std::vector<Point2> p = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  try {
    furthest_site_delaunay2d(&p[0].x, 4);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::DegenerateInput);
  }
}

}  // namespace
