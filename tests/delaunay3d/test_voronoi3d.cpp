// The 3D Voronoi diagram (issue 49) on the CPU executor: its arrays against what the
// tetrahedralisation says independently (every vertex a circumcentre, one per exactly cospherical
// class; one ridge per edge of the Delaunay subdivision with its ring of vertices; each region
// the classes round its point), on general and degenerate input, and an integer grid's known
// diagram.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "del3d_cases.hpp"
#include "gpugeom/voronoi3d.hpp"
#include "gpugeom/predicates.hpp"

using namespace gpugeom;

namespace {
Delaunay3dOptions cpu() {
  Delaunay3dOptions o;
  o.backend = Backend::Cpu;
  return o;
}

// What the arrays must say of any input: every vertex the circumcentre of each of its
// tetrahedra (up to rounding), neighbouring tetrahedra of one class exactly cospherical (the
// public exact predicate), every ridge a ring of distinct consecutive vertices round an edge of
// the tetrahedralisation whose vertices all lie on tetrahedra round that edge, every edge with
// three or more classes round it a ridge, and every region the classes round its point.
void expect_consistent(const std::vector<Point3>& p, const Triangulation3d& t, const Voronoi3d& v) {
  const std::int64_t n = std::int64_t(p.size()), nt = t.num_tetrahedra;
  const std::int64_t nv = std::int64_t(v.vertices.size() / 3);
  ASSERT_EQ(std::int64_t(v.simplex_vertex.size()), nt);
  ASSERT_EQ(std::int64_t(v.region_offsets.size()), n + 1);
  // vertices: circumcentres, one class each
  std::vector<int> seen(std::size_t(nv), 0);
  for (std::int64_t k = 0; k < nt; ++k) {
    const std::int32_t c = v.simplex_vertex[k];
    ASSERT_TRUE(c >= 0 && c < nv);
    seen[c] = 1;
    const double* x = &v.vertices[3 * std::size_t(c)];
    double r[4];
    for (int j = 0; j < 4; ++j) {
      const Point3& q = p[t.tetrahedra[4 * k + j]];
      r[j] = std::hypot(q.x - x[0], q.y - x[1], q.z - x[2]);
    }
    for (int j = 1; j < 4; ++j) EXPECT_NEAR(r[j], r[0], 1e-7 * (1 + r[0])) << "tetrahedron " << k;
    for (int f = 0; f < 4; ++f) {  // a neighbour across a cospherical face: the same vertex
      const std::int32_t o = t.neighbors[4 * k + f];
      if (o < 0) continue;
      std::int32_t d = -1;
      for (int j = 0; j < 4; ++j) {
        const std::int32_t w = t.tetrahedra[4 * std::int64_t(o) + j];
        if (std::find(&t.tetrahedra[4 * k], &t.tetrahedra[4 * k] + 4, w) ==
            &t.tetrahedra[4 * k] + 4)
          d = w;
      }
      const Point3* q[4];
      for (int j = 0; j < 4; ++j) q[j] = &p[t.tetrahedra[4 * k + j]];
      const bool cospherical = insphere(*q[0], *q[1], *q[2], *q[3], p[d]) == 0;
      if (cospherical) EXPECT_EQ(v.simplex_vertex[o], c);
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), nv);
  // the classes round each edge (tetrahedra that hold both ends)
  std::map<std::pair<std::int32_t, std::int32_t>, std::set<std::int32_t>> round;
  for (std::int64_t k = 0; k < nt; ++k)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        std::int32_t a = t.tetrahedra[4 * k + i], b = t.tetrahedra[4 * k + j];
        if (a > b) std::swap(a, b);
        round[{a, b}].insert(v.simplex_vertex[k]);
      }
  const std::int64_t nr = std::int64_t(v.ridge_points.size() / 2);
  ASSERT_EQ(std::int64_t(v.ridge_offsets.size()), nr + 1);
  std::set<std::pair<std::int32_t, std::int32_t>> ridges;
  for (std::int64_t r = 0; r < nr; ++r) {
    std::int32_t a = v.ridge_points[2 * r], b = v.ridge_points[2 * r + 1];
    if (a > b) std::swap(a, b);
    EXPECT_TRUE(ridges.insert({a, b}).second) << "two ridges between " << a << " and " << b;
    const auto it = round.find({a, b});
    ASSERT_NE(it, round.end()) << "ridge " << r << " is on no edge";
    const std::int64_t s = v.ridge_offsets[r], e = v.ridge_offsets[r + 1];
    ASSERT_GE(e - s, 2);
    std::set<std::int32_t> got;
    for (std::int64_t j = s; j < e; ++j) {
      const std::int32_t w = v.ridge_vertices[j];
      EXPECT_TRUE(w == -1 ? j == s : it->second.count(w) == 1) << "ridge " << r;
      EXPECT_NE(w, v.ridge_vertices[j + 1 < e ? j + 1 : s]) << "ridge " << r;
      if (w >= 0) got.insert(w);
    }
    EXPECT_EQ(got, it->second) << "ridge " << r;  // its ring passes every class round the edge
  }
  for (const auto& kv : round)
    if (kv.second.size() >= 3) EXPECT_EQ(ridges.count(kv.first), 1u) << kv.first.first;
  // regions: the classes round each point, -1 first on the hull
  std::vector<std::set<std::int32_t>> cls(static_cast<std::size_t>(n));
  std::vector<char> hull(std::size_t(n), 0);
  for (std::int64_t k = 0; k < nt; ++k)
    for (int j = 0; j < 4; ++j) {
      cls[t.tetrahedra[4 * k + j]].insert(v.simplex_vertex[k]);
      if (t.neighbors[4 * k + j] < 0)
        for (int i = 0; i < 4; ++i)
          if (i != j) hull[t.tetrahedra[4 * k + i]] = 1;
    }
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t src = t.duplicate_of[i] >= 0 ? t.duplicate_of[i] : i;
    std::vector<std::int32_t> want;
    if (hull[src]) want.push_back(-1);
    want.insert(want.end(), cls[src].begin(), cls[src].end());
    const std::vector<std::int32_t> got(v.region_vertices.begin() + v.region_offsets[i],
                                        v.region_vertices.begin() + v.region_offsets[i + 1]);
    EXPECT_EQ(got, want) << "point " << i;
  }
}
}  // namespace

TEST(Voronoi3d, GeneralPosition) {
  const auto p = generate3d("uniform", 3000, 5);
  const auto t = delaunay3d(p, cpu());
  const auto v = voronoi3d(&p.data()->x, std::int64_t(p.size()), t);
  expect_consistent(p, t, v);
  // no five points on a sphere: a vertex per tetrahedron, a ridge per edge
  EXPECT_EQ(v.vertices.size(), 3 * t.num_tetrahedra);
  for (std::size_t k = 0; k < t.num_tetrahedra; ++k) EXPECT_EQ(v.simplex_vertex[k], k);
}

// The Voronoi cells of an integer grid are the unit cubes round its points: one vertex per cube
// of the grid (its eight corners on one sphere), one ridge per pair of neighbours along an axis
// (a square, or on the hull a half-strip or quadrant), none across a face or cube diagonal.
TEST(Voronoi3d, GridIsCubes) {
  const int a = 5, b = 4, c = 3;
  std::vector<Point3> p;
  for (int i = 0; i < a; ++i)
    for (int j = 0; j < b; ++j)
      for (int k = 0; k < c; ++k) p.push_back({double(i), double(j), double(k)});
  p.push_back(p[7]);  // a copy shares its twin's cell
  const std::int64_t n = std::int64_t(p.size());
  const auto t = delaunay3d(p, cpu());
  const auto v = voronoi3d(&p.data()->x, n, t);
  expect_consistent(p, t, v);
  EXPECT_EQ(v.vertices.size() / 3, std::size_t((a - 1) * (b - 1) * (c - 1)));
  for (std::size_t k = 0; k < v.vertices.size(); ++k)
    EXPECT_EQ(v.vertices[k] - std::floor(v.vertices[k]), 0.5);
  const std::size_t pairs = std::size_t((a - 1) * b * c + a * (b - 1) * c + a * b * (c - 1));
  ASSERT_EQ(v.ridge_points.size() / 2, pairs);
  for (std::size_t r = 0; r < pairs; ++r) {
    const Point3 &u = p[v.ridge_points[2 * r]], &w = p[v.ridge_points[2 * r + 1]];
    EXPECT_EQ(std::abs(u.x - w.x) + std::abs(u.y - w.y) + std::abs(u.z - w.z), 1.0);
    const std::int64_t len = v.ridge_offsets[r + 1] - v.ridge_offsets[r];
    const bool open = v.ridge_vertices[v.ridge_offsets[r]] == -1;
    EXPECT_TRUE(open ? len == 2 || len == 3 : len == 4) << r;  // (-1 and 1 or 2, or a square)
  }
  // the centre point's cell: the 8 cubes round it; a corner's: -1 and its one cube
  auto region = [&](std::int64_t i) {
    return std::vector<std::int32_t>(v.region_vertices.begin() + v.region_offsets[i],
                                     v.region_vertices.begin() + v.region_offsets[i + 1]);
  };
  const std::int64_t centre = (2 * b + 1) * c + 1;  // (2, 1, 1)
  EXPECT_EQ(region(centre).size(), 8u);
  EXPECT_EQ(region(0).size(), 2u);
  EXPECT_EQ(region(0)[0], -1);
  EXPECT_EQ(region(n - 1), region(7));
}

TEST(Voronoi3d, DegenerateCases) {
  for (const auto& c : gg_hull3d::degenerate_cases()) {
    SCOPED_TRACE(c.name);
    Triangulation3d t;
    try {
      t = delaunay3d(c.pts, cpu());
    } catch (const Error& e) {  // (the cases without a tetrahedralisation)
      EXPECT_EQ(e.code(), ErrorCode::DegenerateInput) << e.what();
      continue;
    }
    expect_consistent(c.pts, t, voronoi3d(&c.pts.data()->x, std::int64_t(c.pts.size()), t));
  }
}

TEST(Voronoi3d, Errors) {
  const auto p = generate3d("uniform", 100, 5);
  const auto t = delaunay3d(p, cpu());
  EXPECT_THROW((void)voronoi3d(&p.data()->x, 99, t), Error);
  // the device entry on the CPU executor: the host entry's arrays
  DeviceTriangulation3d dt;
  {
    Delaunay3dOptions o = cpu();
    dt = delaunay3d_device(&p.data()->x, 100, o);
  }
  const auto v = voronoi3d(&p.data()->x, 100, t);
  const auto d = voronoi3d_device(&p.data()->x, 100, dt, options_from<Voronoi3dOptions>(cpu()));
  ASSERT_EQ(d.num_vertices, std::int64_t(v.vertices.size() / 3));
  EXPECT_EQ(std::vector<double>(d.vertices.get(), d.vertices.get() + 3 * d.num_vertices),
            std::vector<double>(v.vertices.begin(), v.vertices.end()));
  EXPECT_EQ(std::vector<std::int32_t>(d.ridge_vertices.get(),
                                      d.ridge_vertices.get() + d.num_ridge_vertices),
            std::vector<std::int32_t>(v.ridge_vertices.begin(), v.ridge_vertices.end()));
  EXPECT_THROW((void)voronoi3d_device(&p.data()->x, 99, dt, options_from<Voronoi3dOptions>(cpu())),
               Error);
  // both structures in one call: the same as one after the other
  Triangulation3d t2;
  const auto both = voronoi3d(&p.data()->x, 100, cpu(), &t2);
  EXPECT_EQ(t2.tetrahedra, t.tetrahedra);
  EXPECT_EQ(both.ridge_vertices, v.ridge_vertices);
  EXPECT_EQ(both.region_vertices, v.region_vertices);
}
