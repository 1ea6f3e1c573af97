// Voronoi cells in a box (issue 49) on the CPU executor, against what is known independently:
// the volumes fill the box; an inner cell's volume equals the one summed from the Voronoi
// diagram's ridge polygons (voronoi3d: circumcentres, not cut planes); every cell vertex is no
// nearer to another point than to its own (brute force); the neighbours are symmetric with equal
// face areas and opposite normals; a lattice gives cubes; a periodic box equals the inner copy
// of 27 replicas; bad input gets typed errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "gpugeom/voronoi3d.hpp"
#include "gpugeom/voronoi_cells.hpp"

using namespace gpugeom;

namespace {

std::vector<double> uniform(std::int64_t n, std::uint64_t seed, double lo = 0, double hi = 1) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> p(std::size_t(3 * n));
  for (double& x : p) x = u(g);
  return p;
}

VoronoiCellsOptions box(double lo, double hi, bool px = false, bool py = false, bool pz = false) {
  VoronoiCellsOptions o;
  o.backend = Backend::Cpu;
  for (int d = 0; d < 3; ++d) o.lo[d] = lo, o.hi[d] = hi;
  o.periodic[0] = px, o.periodic[1] = py, o.periodic[2] = pz;
  return o;
}

double sum(const HostVector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

// Cell i's volume from the diagram's ridges (pyramids from the point over each ridge polygon);
// -1 where the cell is unbounded.
double diagram_volume(const std::vector<double>& p, const Voronoi3d& v, std::int64_t i) {
  double vol = 0;
  const std::int64_t nr = std::int64_t(v.ridge_points.size() / 2);
  for (std::int64_t r = 0; r < nr; ++r) {
    if (v.ridge_points[2 * r] != i && v.ridge_points[2 * r + 1] != i) continue;
    const std::int64_t a = v.ridge_offsets[r], b = v.ridge_offsets[r + 1];
    if (v.ridge_vertices[a] < 0) return -1;
    auto rel = [&](std::int64_t k, int d) {
      return v.vertices[3 * v.ridge_vertices[k] + d] - p[3 * i + d];
    };
    double s = 0;
    for (std::int64_t k = a + 1; k + 1 < b; ++k) {
      const double x[3] = {rel(a, 0), rel(a, 1), rel(a, 2)};
      const double y[3] = {rel(k, 0), rel(k, 1), rel(k, 2)};
      const double z[3] = {rel(k + 1, 0), rel(k + 1, 1), rel(k + 1, 2)};
      s += x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0]) +
           x[2] * (y[0] * z[1] - y[1] * z[0]);
    }
    vol += std::fabs(s) / 6;
  }
  return vol;
}

// What any cells must satisfy: consistent offsets, positive volumes filling the box, faces
// whose normals point away from the point, neighbours symmetric (same area, opposite normal,
// per pair of points the same total), and every vertex in the box and no nearer to another point
// than to its own (brute force over `pts`, the points and, periodic, their images).
void expect_cells(const std::vector<double>& p, const VoronoiCells& c, double box_volume,
                  const std::vector<double>& pts) {
  const std::int64_t n = std::int64_t(p.size() / 3);
  ASSERT_EQ(std::int64_t(c.volumes.size()), n);
  ASSERT_EQ(std::int64_t(c.face_offsets.size()), n + 1);
  ASSERT_EQ(std::int64_t(c.vertex_offsets.size()), n + 1);
  const std::int64_t nf = c.face_offsets[n];
  ASSERT_EQ(std::int64_t(c.neighbors.size()), nf);
  ASSERT_EQ(std::int64_t(c.face_vertex_offsets.size()), nf + 1);
  EXPECT_NEAR(sum(c.volumes), box_volume, 1e-12 * box_volume);
  std::map<std::pair<int, int>, double> pair_area;
  for (std::int64_t i = 0; i < n; ++i) {
    EXPECT_GT(c.volumes[i], 0) << i;
    double area = 0;
    for (std::int64_t f = c.face_offsets[i]; f < c.face_offsets[i + 1]; ++f) {
      area += c.face_areas[f];
      EXPECT_GT(c.face_areas[f], 0);
      const int q = c.neighbors[f];
      if (q >= 0) pair_area[{int(i), q}] += c.face_areas[f];
      // counter-clockwise seen from outside: the polygon's area vector along the normal
      double newell[3] = {0, 0, 0};
      const std::int64_t fa = c.face_vertex_offsets[f], fb = c.face_vertex_offsets[f + 1];
      for (std::int64_t k = fa; k < fb; ++k) {
        const double* x = &c.vertices[3 * c.face_vertices[k]];
        const double* y = &c.vertices[3 * c.face_vertices[k + 1 < fb ? k + 1 : fa]];
        newell[0] += (x[1] - y[1]) * (x[2] + y[2]);
        newell[1] += (x[2] - y[2]) * (x[0] + y[0]);
        newell[2] += (x[0] - y[0]) * (x[1] + y[1]);
      }
      double along = 0;
      for (int d = 0; d < 3; ++d) along += newell[d] * c.face_normals[3 * f + d];
      EXPECT_NEAR(along / 2, c.face_areas[f], 1e-9 * c.face_areas[f]);
      // the face's vertices lie on the side the normal points to, away from the point
      for (std::int64_t k = c.face_vertex_offsets[f]; k < c.face_vertex_offsets[f + 1]; ++k) {
        const std::int32_t v = c.face_vertices[k];
        ASSERT_GE(v, c.vertex_offsets[i]);
        ASSERT_LT(v, c.vertex_offsets[i + 1]);
        double dot = 0;
        for (int d = 0; d < 3; ++d)
          dot += (c.vertices[3 * v + d] - p[3 * i + d]) * c.face_normals[3 * f + d];
        EXPECT_GT(dot, 0);
      }
    }
    EXPECT_NEAR(area, c.areas[i], 1e-12 * c.areas[i]);
    for (std::int64_t v = c.vertex_offsets[i]; v < c.vertex_offsets[i + 1]; ++v) {
      const double* x = &c.vertices[3 * v];
      double own = 0;
      for (int d = 0; d < 3; ++d) own += (x[d] - p[3 * i + d]) * (x[d] - p[3 * i + d]);
      for (std::size_t q = 0; q < pts.size() / 3; ++q) {
        double dq = 0;
        for (int d = 0; d < 3; ++d) dq += (x[d] - pts[3 * q + d]) * (x[d] - pts[3 * q + d]);
        ASSERT_GE(dq, own - 1e-9 * (own + 1e-30)) << "cell " << i << " vertex " << v;
      }
    }
  }
  for (const auto& [pq, a] : pair_area) {
    const auto it = pair_area.find({pq.second, pq.first});
    ASSERT_TRUE(it != pair_area.end()) << pq.first << " " << pq.second;
    EXPECT_NEAR(it->second, a, 1e-9 * a);
  }
}

TEST(VoronoiCells, BoundedCellsFillTheBoxAndMatchTheDiagram) {
  const std::int64_t n = 1500;
  const auto p = uniform(n, 7);
  const VoronoiCells c = voronoi_cells(p.data(), n, box(0, 1));
  expect_cells(p, c, 1.0, p);
  EXPECT_EQ(c.stats.attempts, 1);
  // cells no wall cuts are read from the diagram; the others cut from the box
  EXPECT_GT(c.stats.cells_cut, 0);
  EXPECT_LT(c.stats.cells_cut, n / 2);
  // inner cells: the volume summed from the diagram's circumcentres
  Delaunay3dOptions o;
  o.backend = Backend::Cpu;
  const Voronoi3d v = voronoi3d(p.data(), n, o);
  int compared = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const double dv = diagram_volume(p, v, i);
    if (dv < 0) continue;
    bool inside = true;  // (a cell the box does not cut: all its vertices inside)
    for (std::int64_t k = v.region_offsets[i]; k < v.region_offsets[i + 1]; ++k)
      for (int d = 0; d < 3; ++d) {
        const double x = v.vertices[3 * v.region_vertices[k] + d];
        inside &= x > 0 && x < 1;
      }
    if (!inside) continue;
    EXPECT_NEAR(c.volumes[i], dv, 1e-9 * dv) << i;
    ++compared;
  }
  EXPECT_GT(compared, n / 2);
}

TEST(VoronoiCells, LatticeCellsAreCubes) {
  const int m = 5;
  std::vector<double> p;
  for (int z = 0; z < m; ++z)
    for (int y = 0; y < m; ++y)
      for (int x = 0; x < m; ++x)
        for (int c : {x, y, z}) p.push_back((c + 0.5) / m);
  const std::int64_t n = std::int64_t(p.size() / 3);
  for (bool periodic : {false, true}) {
    const VoronoiCells c = voronoi_cells(p.data(), n, box(0, 1, periodic, periodic, periodic));
    expect_cells(p, c, 1.0, p);
    for (std::int64_t i = 0; i < n; ++i) {
      EXPECT_NEAR(c.volumes[i], 1.0 / (m * m * m), 1e-15) << i;
      ASSERT_EQ(c.face_offsets[i + 1] - c.face_offsets[i], 6) << i;  // no sliver faces
      EXPECT_EQ(c.vertex_offsets[i + 1] - c.vertex_offsets[i], 8) << i;
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(c.centroids[3 * i + d], p[3 * i + d], 1e-15);
      const int x = int(i % m), y = int(i / m % m), z = int(i / (m * m));
      std::vector<int> want;  // walls (-1 .. -6) and the six lattice neighbours
      for (int d = 0; d < 3; ++d)
        for (int s : {-1, 1}) {
          int k[3] = {x, y, z};
          k[d] += s;
          if (k[d] < 0 || k[d] >= m) {
            if (!periodic) {
              want.push_back(-1 - (2 * d + (s > 0)));
              continue;
            }
            k[d] = (k[d] + m) % m;
          }
          want.push_back(k[0] + m * k[1] + m * m * k[2]);
        }
      std::vector<int> got(c.neighbors.begin() + c.face_offsets[i],
                           c.neighbors.begin() + c.face_offsets[i + 1]);
      std::sort(want.begin(), want.end());
      std::sort(got.begin(), got.end());
      EXPECT_EQ(got, want) << i;
    }
  }
}

// A periodic box: each cell equals the inner copy's among 27 replicas of the points (its volume
// summed from the replicas' diagram), the faces name original points, none is a wall.
TEST(VoronoiCells, PeriodicCellsEqualTheInnerCopyOfReplicas) {
  const std::int64_t n = 400;
  const auto p = uniform(n, 11, -1, 2);  // (2 units wide, modulo the box [0, 2))
  VoronoiCellsOptions o = box(0, 2, true, true, true);
  const VoronoiCells c = voronoi_cells(p.data(), n, o);
  std::vector<double> w(p);  // the points taken into the box, then the 26 other copies
  for (double& x : w) x = x < 0 ? x + 2 : x;
  std::vector<double> rep(w);
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int z = -1; z <= 1; ++z) {
        if (!a && !b && !z) continue;
        for (std::int64_t i = 0; i < n; ++i) {
          rep.push_back(w[3 * i] + 2 * a);
          rep.push_back(w[3 * i + 1] + 2 * b);
          rep.push_back(w[3 * i + 2] + 2 * z);
        }
      }
  expect_cells(w, c, 8.0, rep);
  EXPECT_EQ(c.stats.cells_cut, 0);  // (no walls: every cell from the diagram)
  Delaunay3dOptions d;
  d.backend = Backend::Cpu;
  const Voronoi3d v = voronoi3d(rep.data(), std::int64_t(rep.size() / 3), d);
  for (std::int64_t i = 0; i < n; ++i) {
    const double dv = diagram_volume(rep, v, i);
    ASSERT_GT(dv, 0);
    EXPECT_NEAR(c.volumes[i], dv, 1e-9 * dv) << i;
    for (std::int64_t f = c.face_offsets[i]; f < c.face_offsets[i + 1]; ++f)
      EXPECT_GE(c.neighbors[f], 0);
  }
}

TEST(VoronoiCells, PeriodicAlongSomeAxes) {
  const std::int64_t n = 300;
  const auto p = uniform(n, 5);
  const VoronoiCells c = voronoi_cells(p.data(), n, box(0, 1, true, false, true));
  std::vector<double> rep(p);
  for (int a = -1; a <= 1; ++a)
    for (int z = -1; z <= 1; ++z) {
      if (!a && !z) continue;
      for (std::int64_t i = 0; i < n; ++i) {
        rep.push_back(p[3 * i] + a);
        rep.push_back(p[3 * i + 1]);
        rep.push_back(p[3 * i + 2] + z);
      }
    }
  expect_cells(p, c, 1.0, rep);
  for (std::int64_t f = 0; f < c.face_offsets[n]; ++f)  // (walls only along y)
    if (c.neighbors[f] < 0) EXPECT_TRUE(c.neighbors[f] == -3 || c.neighbors[f] == -4);
}

TEST(VoronoiCells, FewPointsFlatInputAndDuplicates) {
  // one point: the box; two: halves
  const double one[3] = {0.2, 0.3, 0.4};
  VoronoiCells c = voronoi_cells(one, 1, box(0, 1));
  ASSERT_EQ(c.volumes.size(), 1u);
  EXPECT_NEAR(c.volumes[0], 1, 1e-15);
  EXPECT_EQ(c.face_offsets[1], 6);
  const double two[6] = {0.25, 0.5, 0.5, 0.75, 0.5, 0.5};
  c = voronoi_cells(two, 2, box(0, 1));
  EXPECT_NEAR(c.volumes[0], 0.5, 1e-15);
  EXPECT_NEAR(c.volumes[1], 0.5, 1e-15);
  // one point, periodic: the box, its faces meeting its own images
  c = voronoi_cells(one, 1, box(0, 1, true, true, true));
  EXPECT_NEAR(c.volumes[0], 1, 1e-12);
  for (std::int64_t f = 0; f < c.face_offsets[1]; ++f) EXPECT_EQ(c.neighbors[f], 0);
  // all points on one plane: prisms
  std::vector<double> flat = uniform(50, 3);
  for (std::size_t i = 2; i < flat.size(); i += 3) flat[i] = 0.5;
  c = voronoi_cells(flat.data(), 50, box(0, 1));
  expect_cells(flat, c, 1.0, flat);
  // duplicates: the first keeps the cell, the copy has none
  std::vector<double> d = uniform(100, 9);
  d.insert(d.end(), d.begin() + 30, d.begin() + 33);
  c = voronoi_cells(d.data(), 101, box(0, 1));
  EXPECT_EQ(c.volumes[100], 0);
  EXPECT_EQ(c.face_offsets[101], c.face_offsets[100]);
  EXPECT_NEAR(sum(c.volumes), 1, 1e-12);
  // none
  c = voronoi_cells(nullptr, 0, box(0, 1));
  EXPECT_EQ(c.volumes.size(), 0u);
  ASSERT_EQ(c.face_offsets.size(), 1u);
}

TEST(VoronoiCells, SameBitsOnAnyThreadCount) {
  const std::int64_t n = 2000;
  const auto p = uniform(n, 21);
  VoronoiCellsOptions a = box(0, 1, true, true, true), b = a;
  a.threads = 1;
  const VoronoiCells x = voronoi_cells(p.data(), n, a), y = voronoi_cells(p.data(), n, b);
  EXPECT_TRUE(x.volumes == y.volumes);
  EXPECT_TRUE(x.neighbors == y.neighbors);
  EXPECT_TRUE(x.face_normals == y.face_normals);
  EXPECT_TRUE(x.vertices == y.vertices);
  EXPECT_TRUE(x.face_vertices == y.face_vertices);
  // without the polygons: the same measures and faces, no polygon arrays
  b.polygons = false;
  const VoronoiCells z = voronoi_cells(p.data(), n, b);
  EXPECT_TRUE(z.volumes == x.volumes);
  EXPECT_TRUE(z.centroids == x.centroids);
  EXPECT_TRUE(z.neighbors == x.neighbors);
  EXPECT_TRUE(z.face_areas == x.face_areas);
  EXPECT_TRUE(z.face_normals == x.face_normals);
  EXPECT_TRUE(z.vertices.empty() && z.face_vertices.empty() && z.face_vertex_offsets.empty());
}

// The caller's arrays (VoronoiCellsOptions::into), from both entries: the same values as the
// library's arrays, the library's left empty, the counts set; a short array is refused before
// anything is written.
TEST(VoronoiCells, IntoCallersArrays) {
  const std::int64_t n = 500;
  const auto p = uniform(n, 23);
  const VoronoiCellsOptions o = box(0, 1, true, false, false);
  const VoronoiCells ref = voronoi_cells(p.data(), n, o);
  const std::int64_t nf = std::int64_t(ref.neighbors.size()),
                     ne = std::int64_t(ref.face_vertices.size()),
                     nv = std::int64_t(ref.vertices.size() / 3);
  ASSERT_EQ(ref.num_faces, nf);
  ASSERT_EQ(ref.num_face_vertices, ne);
  ASSERT_EQ(ref.num_vertices, nv);
  for (bool device : {false, true}) {
    SCOPED_TRACE(device ? "device entry" : "host entry");
    std::vector<double> vol(std::size_t(n), 7), cen(std::size_t(3 * n), 7),
        fa(std::size_t(nf + 2), 7), vx(std::size_t(3 * nv), 7);
    std::vector<std::int64_t> foff(std::size_t(n + 1), 7), fvo(std::size_t(nf + 1), 7);
    std::vector<std::int32_t> nb(std::size_t(nf), 7), fv(std::size_t(ne), 7);
    VoronoiCellsOptions mine = o;
    mine.into.volumes = {vol.data(), n};
    mine.into.centroids = {cen.data(), 3 * n};
    mine.into.face_areas = {fa.data(), nf + 2};
    mine.into.vertices = {vx.data(), 3 * nv};
    mine.into.face_offsets = {foff.data(), n + 1};
    mine.into.face_vertex_offsets = {fvo.data(), nf + 1};
    mine.into.neighbors = {nb.data(), nf};
    mine.into.face_vertices = {fv.data(), ne};
    if (device) {
      const DeviceVoronoiCells r = voronoi_cells_device(p.data(), n, mine);
      EXPECT_FALSE(r.volumes || r.centroids || r.face_areas || r.vertices || r.face_offsets ||
                   r.face_vertex_offsets || r.neighbors || r.face_vertices);
      ASSERT_TRUE(r.areas && r.face_normals && r.vertex_offsets);
      EXPECT_EQ(r.num_faces, nf);
      EXPECT_TRUE(std::equal(ref.areas.begin(), ref.areas.end(), r.areas.get()));
    } else {
      const VoronoiCells r = voronoi_cells(p.data(), n, mine);
      EXPECT_TRUE(r.volumes.empty() && r.centroids.empty() && r.face_areas.empty() &&
                  r.vertices.empty() && r.face_offsets.empty() && r.face_vertex_offsets.empty() &&
                  r.neighbors.empty() && r.face_vertices.empty());
      EXPECT_TRUE(r.areas == ref.areas);
      EXPECT_TRUE(r.face_normals == ref.face_normals);
      EXPECT_EQ(r.num_faces, nf);
      EXPECT_EQ(r.num_vertices, nv);
    }
    EXPECT_TRUE(vol == ref.volumes);
    EXPECT_TRUE(cen == ref.centroids);
    EXPECT_TRUE(std::vector<double>(fa.begin(), fa.begin() + nf) == ref.face_areas);
    EXPECT_EQ(fa[std::size_t(nf)], 7.0);  // (nothing past the result's length)
    EXPECT_TRUE(vx == ref.vertices);
    EXPECT_TRUE(foff == ref.face_offsets);
    EXPECT_TRUE(fvo == ref.face_vertex_offsets);
    EXPECT_TRUE(nb == ref.neighbors);
    EXPECT_TRUE(fv == ref.face_vertices);
    // One array too short: refused, and nothing written.
    std::vector<double> vol2(std::size_t(n), 7);
    std::vector<std::int32_t> fv2(std::size_t(ne - 1), 7);
    VoronoiCellsOptions short_one = o;
    short_one.into.volumes = {vol2.data(), n};
    short_one.into.face_vertices = {fv2.data(), ne - 1};
    try {
      if (device)
        (void)voronoi_cells_device(p.data(), n, short_one);
      else
        (void)voronoi_cells(p.data(), n, short_one);
      ADD_FAILURE() << "a short face_vertices taken";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
      EXPECT_NE(std::string(e.what()).find("into.face_vertices holds " + std::to_string(ne - 1)),
                std::string::npos)
          << e.what();
    }
    EXPECT_TRUE(std::all_of(vol2.begin(), vol2.end(), [](double x) { return x == 7; }));
    EXPECT_TRUE(std::all_of(fv2.begin(), fv2.end(), [](std::int32_t x) { return x == 7; }));
  }
}

TEST(VoronoiCells, BadInputGetsTypedErrors) {
  const double in[3] = {0.5, 0.5, 1.5}, nan[3] = {0.5, NAN, 0.5};
  auto code = [](auto f) {
    try {
      f();
    } catch (const Error& e) {
      return e.code();
    }
    return ErrorCode::Internal;
  };
  EXPECT_EQ(code([&] { voronoi_cells(in, 1, box(0, 1)); }), ErrorCode::InvalidInput);
  EXPECT_EQ(code([&] { voronoi_cells(nan, 1, box(0, 1, true, true, true)); }),
            ErrorCode::InvalidInput);
  EXPECT_EQ(code([&] { voronoi_cells(in, 1, box(1, 1)); }), ErrorCode::InvalidArgument);
  // outside along an axis that wraps: taken into the box
  const VoronoiCells c = voronoi_cells(in, 1, box(0, 1, false, false, true));
  EXPECT_NEAR(c.centroids[2], 0.5, 1e-12);
}

}  // namespace
