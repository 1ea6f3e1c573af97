// 2D Delaunay on the CPU executor: the checker on every distribution and degenerate input,
// errors, and the Voronoi diagram.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "../common/caller_arrays.hpp"
#include "../common/first_copies.hpp"
#include "gpugeom/locate.hpp"
#include "gpugeom/predicates.hpp"
#include "../common/on_host_threads.hpp"
#include "del2d_cases.hpp"
#include "../common/tuning.hpp"

using namespace gpugeom;
using gg_del2d::expect_valid;
using Capacities = detail::Tuning::Del2d;  // (the flip rounds' capacities forced)

namespace {
Delaunay2dOptions cpu() {
  Delaunay2dOptions o;
  o.backend = Backend::Cpu;
  return o;
}
}  // namespace

TEST(Delaunay2d, Distributions) {
  for (const auto& c : gg_del2d::distribution_cases({3, 4, 10, 100, 1000, 30000}, 11)) {
    SCOPED_TRACE(c.name);
    if (c.name.rfind("two_segments", 0) == 0 && c.pts.size() < 4) continue;
    expect_valid(c.pts, delaunay2d(c.pts, cpu()));
  }
}

TEST(Delaunay2d, Degenerate) {
  std::int64_t flat = 0;
  for (const auto& c : gg_del2d::degenerate_cases()) {
    SCOPED_TRACE(c.name);
    const auto t = delaunay2d(c.pts, cpu());
    expect_valid(c.pts, t);
    flat += t.stats.flat_triangles;
  }
  // collinear hull points: some case must leave flat triangles for the final peel to remove
  EXPECT_GT(flat, 0);
}

// The perturbation depends on the points alone (src/predicates/sos.hpp): points added far away
// change the box and the curve order of every point, yet each triangle of the first run whose
// circumcircle has every new point strictly outside is in the second run. On grids and
// cocircular sets most choices are the perturbation's, so an order-dependent one fails this.
TEST(Delaunay2d, PerturbationDependsOnThePointsAlone) {
  const std::vector<Point2> far = {{-1e5, 3.5}, {9e4, -8e4}, {2.5, 1e6}};
  for (const auto& c : gg_del2d::degenerate_cases()) {
    if (c.name != "grid 31x34" && c.name != "grid 7x10" && c.name != "big integer circle" &&
        c.name != "square outline")
      continue;
    SCOPED_TRACE(c.name);
    auto more = c.pts;
    more.insert(more.end(), far.begin(), far.end());
    const auto a = delaunay2d(c.pts, cpu());
    const auto b = delaunay2d(more, cpu());
    expect_valid(more, b);
    auto key = [](std::int32_t x, std::int32_t y, std::int32_t z) {
      std::array<std::int32_t, 3> k{x, y, z};
      std::sort(k.begin(), k.end());
      return k;
    };
    std::set<std::array<std::int32_t, 3>> in_b;
    for (std::size_t t = 0; t < b.num_triangles; ++t)
      in_b.insert(key(b.triangles[3 * t], b.triangles[3 * t + 1], b.triangles[3 * t + 2]));
    std::size_t checked = 0, kept = 0;
    for (std::size_t t = 0; t < a.num_triangles; ++t) {
      const std::int32_t* v = &a.triangles[3 * t];
      const Point2 &p0 = c.pts[std::size_t(v[0])], &p1 = c.pts[std::size_t(v[1])],
                   &p2 = c.pts[std::size_t(v[2])];
      const int o = orient2d(p0, p1, p2);
      bool clear = true;
      for (const Point2& q : far) clear = clear && incircle(p0, p1, p2, q) * o < 0;
      if (!clear) continue;
      ++checked;
      kept += in_b.count(key(v[0], v[1], v[2]));
    }
    EXPECT_GT(checked, a.num_triangles / 2);
    EXPECT_EQ(kept, checked);
  }
}

// prepare_device never throws (no device, a device that does not exist), and a computation on
// the automatic backend after it gives the same result as without.
TEST(Delaunay2d, PrepareDeviceIsHarmless) {
  const auto pts = generate2d("uniform", 5000, 3);
  Delaunay2dOptions o;
  o.backend = Backend::Cpu;
  const auto ref = delaunay2d(pts, o);
  prepare_device(12345);
  prepare_device();
  o.backend = Backend::Auto;
  const auto r = delaunay2d(pts, o);
  EXPECT_EQ(r.triangles, ref.triangles);
}

TEST(Delaunay2d, Errors) {
  auto code = [](const std::vector<Point2>& p) {
    try {
      delaunay2d(p, cpu());
    } catch (const Error& e) {
      EXPECT_FALSE(std::string(e.what()).empty());
      return e.code();
    }
    return ErrorCode::Cuda;  // "no error": no test expects this code
  };
  const double nan = std::nan(""), inf = HUGE_VAL;
  EXPECT_EQ(code({}), ErrorCode::DegenerateInput);
  EXPECT_EQ(code({{0, 0}, {1, 0}}), ErrorCode::DegenerateInput);
  EXPECT_EQ(code({{0, 0}, {1, 1}, {0, 0}, {1, 1}}), ErrorCode::DegenerateInput);  // 2 distinct
  EXPECT_EQ(code({{0, 0}, {1, 1}, {2, 2}, {3, 3}, {1, 1}}), ErrorCode::DegenerateInput);
  EXPECT_EQ(code({{0, 0}, {1, 0}, {0, nan}}), ErrorCode::InvalidInput);
  EXPECT_EQ(code({{0, 0}, {1, 0}, {inf, 1}}), ErrorCode::InvalidInput);
  EXPECT_EQ(code({{0, 0}, {1, 0}, {1e300, 1}}), ErrorCode::InvalidInput);  // beyond exact range
  // the collinear message names the case
  try {
    delaunay2d(std::vector<Point2>{{0, 0}, {1, 2}, {2, 4}, {0.5, 1}}, cpu());
    FAIL() << "collinear input accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("one line"), std::string::npos) << e.what();
  }
  // nearly collinear is not collinear: exactly decided
  const auto t = delaunay2d(std::vector<Point2>{{0, 0}, {1, 1}, {2, 2 + 1e-15}}, cpu());
  EXPECT_EQ(t.num_triangles, 1u);
}

TEST(Delaunay2d, DuplicatesMapToFirst) {
  std::vector<Point2> p{{0, 0}, {1, 0}, {0, 1}, {1, 0}, {0, 0}, {1, 1}, {1, 0}};
  const auto t = delaunay2d(p, cpu());
  EXPECT_EQ(t.duplicate_of, (std::vector<std::int32_t>{-1, -1, -1, 1, 0, -1, 1}));
  EXPECT_EQ(t.num_duplicates, 3);
  EXPECT_EQ(t.num_triangles, 2u);
}

// Both executors and every thread count must give the same arrays: the algorithm's choices
// never depend on timing.
// The same arrays whatever the thread count: every choice (votes, chosen points, list order)
// is a function of the input, never of which thread came first.
TEST(Delaunay2d, SameForEveryThreadCount) {
  for (const char* d : {"gaussian", "grid", "circle"}) {
    const auto p = generate2d(d, 20000, 3);
    Delaunay2dOptions o = cpu();
    o.threads = 1;
    const auto ref = delaunay2d(p, o);
    for (int t : {2, 3, 0}) {
      o.threads = t;
      const auto r = delaunay2d(p, o);
      EXPECT_EQ(r.triangles, ref.triangles) << d << ", " << t << " threads";
      EXPECT_EQ(r.neighbors, ref.neighbors) << d << ", " << t << " threads";
      EXPECT_EQ(r.stats.flips, ref.stats.flips);
    }
  }
}

// Several host threads, each with its own call (and thread count), at once: each gets the
// result it would get alone.
TEST(Delaunay2d, ConcurrentCallsFromHostThreads) {
  const auto p = generate2d("uniform", 30000, 9);
  gg_test::expect_concurrent_calls_agree(
      [&](int threads) {
        Delaunay2dOptions o = cpu();
        o.threads = threads;
        return delaunay2d(p, o);
      },
      [](const Triangulation2d& ref, const Triangulation2d& got) {
        EXPECT_EQ(got.triangles, ref.triangles);
        EXPECT_EQ(got.neighbors, ref.neighbors);
      });
}

TEST(Delaunay2d, Voronoi) {
  // a square grid's centre point has the unit square around it as its cell
  std::vector<Point2> p;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.push_back({double(i), double(j)});
  const auto t = delaunay2d(p, cpu());
  const auto v = voronoi2d(&p.data()->x, 9, t);
  ASSERT_EQ(v.cell_offsets.size(), 10u);
  // each square's two triangles share one circle exactly: one vertex each (issue 49), 4 in all
  ASSERT_EQ(v.vertices.size(), 8u);
  ASSERT_EQ(v.simplex_vertex.size(), t.num_triangles);
  // centre (index 4): bounded, its vertices the four cell corners, once each
  std::vector<std::pair<double, double>> corners;
  for (std::int64_t j = v.cell_offsets[4]; j < v.cell_offsets[5]; ++j) {
    const std::int32_t w = v.cell_vertices[j];
    ASSERT_GE(w, 0);
    corners.push_back({v.vertices[2 * w], v.vertices[2 * w + 1]});
  }
  std::sort(corners.begin(), corners.end());
  EXPECT_EQ(corners, (std::vector<std::pair<double, double>>{
                         {0.5, 0.5}, {0.5, 1.5}, {1.5, 0.5}, {1.5, 1.5}}));
  // every other point is on the hull: unbounded; a corner's cell has one vertex, an edge's two
  for (int i = 0; i < 9; ++i)
    if (i != 4) {
      EXPECT_EQ(v.cell_vertices[v.cell_offsets[i]], -1) << i;
      EXPECT_EQ(v.cell_offsets[i + 1] - v.cell_offsets[i], i % 2 ? 3 : 2) << i;
    }
  // ridges: one per edge of the grid (the squares' diagonals have none), none of length zero
  EXPECT_EQ(v.ridge_points.size() / 2, 12u);
  for (std::size_t r = 0; r < v.ridge_vertices.size() / 2; ++r) {
    EXPECT_NE(v.ridge_vertices[2 * r], v.ridge_vertices[2 * r + 1]);
    const std::int32_t a = v.ridge_points[2 * r], b = v.ridge_points[2 * r + 1];
    EXPECT_EQ(std::abs(p[a].x - p[b].x) + std::abs(p[a].y - p[b].y), 1.0);
  }
  // clipped cells tile the box: areas sum to the box area
  const auto c = clip_voronoi_cells(&p.data()->x, 9, t, v, -1, -1, 3, 3);
  double total = 0;
  for (int i = 0; i < 9; ++i) {
    double a = 0;
    const std::int64_t b = c.offsets[i], e = c.offsets[i + 1];
    for (std::int64_t j = b; j < e; ++j) {
      const std::int64_t k = j + 1 < e ? j + 1 : b;
      a += c.xy[2 * j] * c.xy[2 * k + 1] - c.xy[2 * k] * c.xy[2 * j + 1];
    }
    EXPECT_GT(a, 0) << i;  // counter-clockwise
    total += a / 2;
    if (i == 4) EXPECT_NEAR(a / 2, 1.0, 1e-12);
  }
  EXPECT_NEAR(total, 16.0, 1e-9);
}

// Triangles whose points lie on one circle exactly share one Voronoi vertex (issue 49): on every
// degenerate case with integer coordinates, the vertices are the classes of triangles joined
// across exactly cocircular edges (decided here in 128-bit integers), no ridge joins a vertex to
// itself and no cell repeats a vertex.
TEST(Delaunay2d, VoronoiMergesCocircularTriangles) {
  using I = __int128;
  int tested = 0;
  for (const auto& c : gg_del2d::degenerate_cases()) {
    const bool integer = std::all_of(c.pts.begin(), c.pts.end(), [](const Point2& q) {
      return q.x == std::floor(q.x) && q.y == std::floor(q.y) && std::abs(q.x) < 1e6 &&
             std::abs(q.y) < 1e6;
    });
    if (!integer || c.pts.size() < 3) continue;
    SCOPED_TRACE(c.name);
    ++tested;
    const std::int64_t n = std::int64_t(c.pts.size());
    const auto t = delaunay2d(c.pts, cpu());
    const auto v = voronoi2d(&c.pts.data()->x, n, t);
    const std::int64_t nt = t.num_triangles;
    ASSERT_EQ(std::int64_t(v.simplex_vertex.size()), nt);
    auto cocircular = [&](std::int64_t a, std::int64_t b) {
      std::int32_t d = -1;  // b's vertex that is not a's
      for (int k = 0; k < 3; ++k) {
        const std::int32_t w = t.triangles[3 * b + k];
        if (w != t.triangles[3 * a] && w != t.triangles[3 * a + 1] && w != t.triangles[3 * a + 2])
          d = w;
      }
      I m[3][3];
      for (int k = 0; k < 3; ++k) {
        const Point2& q = c.pts[t.triangles[3 * a + k]];
        const I x = I(q.x) - I(c.pts[d].x), y = I(q.y) - I(c.pts[d].y);
        m[k][0] = x, m[k][1] = y, m[k][2] = x * x + y * y;
      }
      return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]) ==
             0;
    };
    std::vector<std::int64_t> root(static_cast<std::size_t>(nt));
    for (std::int64_t i = 0; i < nt; ++i) root[i] = i;
    auto find = [&](std::int64_t x) {
      while (root[x] != x) x = root[x];
      return x;
    };
    for (std::int64_t a = 0; a < nt; ++a)
      for (int k = 0; k < 3; ++k) {
        const std::int32_t b = t.neighbors[3 * a + k];
        if (b > a && cocircular(a, b)) {
          const std::int64_t ra = find(a), rb = find(b);
          root[std::max(ra, rb)] = std::min(ra, rb);
        }
      }
    std::map<std::int64_t, std::int32_t> vertex_of_class;
    for (std::int64_t a = 0; a < nt; ++a) {
      const auto [it, fresh] = vertex_of_class.emplace(find(a), v.simplex_vertex[a]);
      EXPECT_EQ(it->second, v.simplex_vertex[a]) << "triangle " << a;
      (void)fresh;
    }
    EXPECT_EQ(v.vertices.size(), 2 * vertex_of_class.size());
    std::set<std::int32_t> named;
    for (const auto& kv : vertex_of_class) named.insert(kv.second);
    EXPECT_EQ(named.size(), vertex_of_class.size());  // one vertex per class
    for (std::size_t r = 0; r < v.ridge_vertices.size() / 2; ++r)
      EXPECT_NE(v.ridge_vertices[2 * r], v.ridge_vertices[2 * r + 1]) << "ridge " << r;
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t b = v.cell_offsets[i], e = v.cell_offsets[i + 1];
      for (std::int64_t j = b; e - b > 1 && j < e; ++j)
        EXPECT_NE(v.cell_vertices[j], v.cell_vertices[j + 1 < e ? j + 1 : b]) << "cell " << i;
    }
  }
  EXPECT_GE(tested, 5);
}

// Every vertex is its triangles' circumcentre, finite, on every degenerate case, coordinates of
// 10^-30 and 10^40 together included (taken from the far corner, the circumcentre of a triangle
// with two near corners was 0/0).
TEST(Delaunay2d, VoronoiVerticesAreCircumcentres) {
  for (const auto& c : gg_del2d::degenerate_cases()) {
    Triangulation2d t;
    try {
      t = delaunay2d(c.pts, cpu());
    } catch (const Error&) {
      continue;  // (no triangulation: tested elsewhere)
    }
    SCOPED_TRACE(c.name);
    const auto v = voronoi2d(&c.pts.data()->x, std::int64_t(c.pts.size()), t);
    for (std::size_t k = 0; k < t.num_triangles; ++k) {
      const double* x = &v.vertices[2 * std::size_t(v.simplex_vertex[k])];
      double r[3];
      for (int j = 0; j < 3; ++j) {
        const Point2& q = c.pts[t.triangles[3 * k + j]];
        r[j] = std::hypot(q.x - x[0], q.y - x[1]);
      }
      ASSERT_TRUE(std::isfinite(x[0]) && std::isfinite(x[1])) << "triangle " << k;
      for (int j = 1; j < 3; ++j) EXPECT_NEAR(r[j], r[0], 1e-9 * r[0]) << "triangle " << k;
    }
  }
}

TEST(Delaunay2d, VoronoiCellsTileTheBox) {
  const auto p = generate2d("uniform", 3000, 9);
  const auto t = delaunay2d(p, cpu());
  const auto v = voronoi2d(&p.data()->x, 3000, t);
  const auto c = clip_voronoi_cells(&p.data()->x, 3000, t, v, -0.5, -0.5, 1.5, 1.5);
  double total = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::int64_t b = c.offsets[i], e = c.offsets[i + 1];
    double a = 0;
    for (std::int64_t j = b; j < e; ++j) {
      const std::int64_t k = j + 1 < e ? j + 1 : b;
      a += c.xy[2 * j] * c.xy[2 * k + 1] - c.xy[2 * k] * c.xy[2 * j + 1];
    }
    total += a / 2;
    // the site lies in its own cell: its bounded cell vertices are circumcentres of its star
    // (in general position one per triangle)
    for (std::int64_t j = v.cell_offsets[i]; j < v.cell_offsets[i + 1]; ++j) {
      const std::int32_t w = v.cell_vertices[j];
      if (w < 0) continue;
      ASSERT_EQ(v.simplex_vertex[std::size_t(w)], w);
      const std::int32_t* tri = &t.triangles[3 * std::size_t(w)];
      EXPECT_TRUE(tri[0] == i || tri[1] == i || tri[2] == i);
    }
  }
  EXPECT_NEAR(total, 4.0, 1e-9);
}

#ifdef GG_HAVE_CGAL
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

// In general position the Delaunay triangulation is unique: the triangle sets must be equal.
TEST(Delaunay2d, SameAsCgal) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, K>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb>;
  using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
  for (const char* d : {"uniform", "gaussian", "thin_circle"})
    for (std::int64_t n : {100, 5000, 100000}) {
      SCOPED_TRACE(std::string(d) + " " + std::to_string(n));
      const auto p = generate2d(d, n, 21);
      std::vector<std::pair<K::Point_2, std::int32_t>> in;
      for (std::int64_t i = 0; i < n; ++i)
        in.push_back({K::Point_2(p[i].x, p[i].y), std::int32_t(i)});
      DT dt(in.begin(), in.end());
      auto canon = [](std::int32_t a, std::int32_t b, std::int32_t c) {
        // rotate so the smallest comes first (orientation kept)
        if (b < a && b < c) return std::array<std::int32_t, 3>{b, c, a};
        if (c < a && c < b) return std::array<std::int32_t, 3>{c, a, b};
        return std::array<std::int32_t, 3>{a, b, c};
      };
      std::vector<std::array<std::int32_t, 3>> ref, got;
      for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
        ref.push_back(canon(f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()));
      const auto t = delaunay2d(p, cpu());
      for (std::size_t i = 0; i < t.num_triangles; ++i)
        got.push_back(canon(t.triangles[3 * i], t.triangles[3 * i + 1], t.triangles[3 * i + 2]));
      std::sort(ref.begin(), ref.end());
      std::sort(got.begin(), got.end());
      EXPECT_EQ(got, ref);
    }
}

// CGAL's symbolic perturbation of the in-circle test (the lexicographically largest point
// first) and ours give the same answers, so the sets are equal on degenerate input too. CGAL
// keeps one copy of a repeated point, not always the first: copies are compared as the first.
TEST(Delaunay2d, SameAsCgalOnDegenerateInput) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, K>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb>;
  using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
  for (const auto& c : gg_del2d::degenerate_cases()) {
    SCOPED_TRACE(c.name);
    const auto first = gg_test::first_copies<2>(c.pts, [](const Point2& p) {
      return std::array<double, 2>{p.x, p.y};
    });
    std::vector<std::pair<K::Point_2, std::int32_t>> in;
    std::size_t distinct = 0;
    for (std::size_t i = 0; i < c.pts.size(); ++i) {
      in.push_back({K::Point_2(c.pts[i].x, c.pts[i].y), first[i]});
      distinct += first[i] == std::int32_t(i);
    }
    if (distinct < 3) continue;
    DT dt(in.begin(), in.end());
    auto key = [](std::int32_t a, std::int32_t b, std::int32_t c3) {
      std::array<std::int32_t, 3> k{a, b, c3};
      std::sort(k.begin(), k.end());
      return k;
    };
    std::set<std::array<std::int32_t, 3>> want, got;
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
      want.insert(key(f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()));
    const auto t = delaunay2d(c.pts, cpu());
    for (std::size_t i = 0; i < t.num_triangles; ++i)
      got.insert(key(t.triangles[3 * i], t.triangles[3 * i + 1], t.triangles[3 * i + 2]));
    EXPECT_EQ(got, want);
  }
}
#endif

// The device entry on the CPU executor (its "device" memory is host memory) gives the host
// entry's result; the caller's arrays take the outputs on both entries; arrays too short for the
// result are refused before anything is written.
TEST(Delaunay2d, DeviceEntryAndCallerArrays) {
  using gg_test::CallerArray;
  using gg_test::host_prefix;
  for (const char* d : {"uniform", "grid"}) {
    SCOPED_TRACE(d);
    auto p = generate2d(d, 3000, 5);
    for (int k = 0; k < 40; ++k) p.push_back(p[std::size_t(17 * k)]);  // duplicates
    const std::int64_t n = std::int64_t(p.size());
    const double* xy = &p.data()->x;
    const auto ref = delaunay2d(p, cpu());
    const std::int64_t nt = ref.num_triangles;
    ASSERT_EQ(ref.triangles.size(), std::size_t(3 * nt));
    ASSERT_LE(nt, delaunay2d_max_triangles(n));

    const auto dv = delaunay2d_device(xy, n, cpu());
    EXPECT_EQ(dv.backend, Backend::Cpu);
    ASSERT_EQ(dv.num_triangles, nt);
    EXPECT_EQ(dv.num_duplicates, ref.num_duplicates);
    EXPECT_EQ(host_prefix(dv.triangles, 3 * nt), ref.triangles);
    EXPECT_EQ(host_prefix(dv.neighbors, 3 * nt), ref.neighbors);
    EXPECT_EQ(host_prefix(dv.duplicate_of, n), ref.duplicate_of);

    const std::int64_t cap = 3 * delaunay2d_max_triangles(n);
    for (bool device : {false, true}) {
      SCOPED_TRACE(device ? "device entry" : "host entry");
      CallerArray<std::int32_t> t(cap, 7), nb(cap, 7), dup(n, 7);
      auto o = cpu();
      o.into = {t.buf(), nb.buf(), dup.buf()};
      std::int64_t count = 0;
      if (device) {
        const auto r = delaunay2d_device(xy, n, o);
        EXPECT_FALSE(r.triangles || r.neighbors || r.duplicate_of);
        count = r.num_triangles;
      } else {
        const auto r = delaunay2d(xy, n, o);
        EXPECT_TRUE(r.triangles.empty() && r.neighbors.empty() && r.duplicate_of.empty());
        count = r.num_triangles;
      }
      ASSERT_EQ(count, nt);
      EXPECT_EQ(host_prefix(t.v.data(), 3 * nt), ref.triangles);
      EXPECT_EQ(host_prefix(nb.v.data(), 3 * nt), ref.neighbors);
      EXPECT_EQ(dup.v, ref.duplicate_of);
      // One array too short: refused once the count is known, and nothing written anywhere.
      CallerArray<std::int32_t> t2(3 * nt - 1, 7), nb2(cap, 7);
      o.into = {t2.buf(), nb2.buf(), {}};
      gg_test::expect_refused(
          [&] { device ? (void)delaunay2d_device(xy, n, o) : (void)delaunay2d(xy, n, o); },
          "into.triangles holds " + std::to_string(3 * nt - 1) +
              " elements; this result needs "
              "at least " +
              std::to_string(3 * nt));
      EXPECT_TRUE(t2.untouched(7) && nb2.untouched(7));
    }
    // The Voronoi diagram needs the arrays in the result, and says so.
    auto o = cpu();
    CallerArray<std::int32_t> t(cap, 0);
    o.into.triangles = t.buf();
    const auto r = delaunay2d(xy, n, o);
    gg_test::expect_refused([&] { (void)voronoi2d(xy, n, r); }, "into");
  }
}

// The Voronoi diagram computed on the executor from a device triangulation (CPU executor: host
// memory) equals the host's, array for array, duplicates and hull cells included.
TEST(Delaunay2d, VoronoiDeviceEntry) {
  using gg_test::host_prefix;
  for (const char* d : {"uniform", "grid", "circle"}) {
    SCOPED_TRACE(d);
    auto p = generate2d(d, 2000, 3);
    for (int k = 0; k < 20; ++k) p.push_back(p[std::size_t(13 * k)]);  // duplicates
    const std::int64_t n = std::int64_t(p.size());
    const double* xy = &p.data()->x;
    const auto tri = delaunay2d(p, cpu());
    const auto ref = voronoi2d(xy, n, tri);
    const auto dt = delaunay2d_device(xy, n, cpu());
    const auto v = voronoi2d_device(xy, n, dt);
    EXPECT_EQ(v.backend, Backend::Cpu);
    ASSERT_EQ(v.num_vertices, std::int64_t(ref.vertices.size() / 2));
    ASSERT_EQ(v.num_ridges, std::int64_t(ref.ridge_points.size() / 2));
    ASSERT_EQ(v.num_cell_vertices, std::int64_t(ref.cell_vertices.size()));
    EXPECT_EQ(host_prefix(v.vertices, 2 * v.num_vertices), ref.vertices);
    EXPECT_EQ(host_prefix(v.ridge_points, 2 * v.num_ridges), ref.ridge_points);
    EXPECT_EQ(host_prefix(v.ridge_vertices, 2 * v.num_ridges), ref.ridge_vertices);
    EXPECT_EQ(host_prefix(v.ridge_directions, 2 * v.num_ridges), ref.ridge_directions);
    EXPECT_EQ(host_prefix(v.cell_offsets, n + 1), ref.cell_offsets);
    EXPECT_EQ(host_prefix(v.cell_vertices, v.num_cell_vertices), ref.cell_vertices);
    // A triangulation of other points is refused.
    gg_test::expect_refused([&] { (void)voronoi2d_device(xy, n - 1, dt); }, "belong");
    // The one-call host entry: the same triangulation and diagram.
    Triangulation2d t2;
    const auto both = voronoi2d(xy, n, cpu(), &t2);
    EXPECT_EQ(t2.triangles, tri.triangles);
    EXPECT_EQ(both.vertices, ref.vertices);
    EXPECT_EQ(both.ridge_vertices, ref.ridge_vertices);
    EXPECT_EQ(both.cell_vertices, ref.cell_vertices);
  }
  EXPECT_THROW((void)voronoi2d(nullptr, 2, cpu()), Error);
}

// The diagram of a kept triangulation after removals (issue 47): a removed point has an empty
// cell, every other point the cell a fresh diagram of the points left gives it; both entries.
TEST(Delaunay2d, VoronoiOfAKeptTriangulationWithRemovedPoints) {
  auto p = generate2d("grid", 1500, 4);
  const std::int64_t n = std::int64_t(p.size());
  const double* xy = &p.data()->x;
  DynamicDelaunay2d d(xy, n, cpu());
  std::vector<std::int32_t> gone;
  for (std::int32_t i = 5; i < n; i += 7) gone.push_back(i);
  d.remove(gone.data(), std::int64_t(gone.size()));
  const auto v = voronoi2d(xy, n, d.triangulation());
  const auto dv = voronoi2d_device(xy, n, d.device_triangulation());
  EXPECT_EQ(gg_test::host_prefix(dv.cell_offsets, n + 1), v.cell_offsets);
  std::vector<Point2> live;
  std::vector<std::int64_t> ids;
  std::vector<char> removed(std::size_t(n), 0);
  for (auto i : gone) removed[std::size_t(i)] = 1;
  for (std::int64_t i = 0; i < n; ++i)
    if (!removed[std::size_t(i)]) live.push_back(p[std::size_t(i)]), ids.push_back(i);
  const auto f = voronoi2d(&live.data()->x, std::int64_t(live.size()), delaunay2d(live, cpu()));
  EXPECT_EQ(v.vertices.size(), f.vertices.size());
  EXPECT_EQ(v.ridge_points.size(), f.ridge_points.size());
  for (std::int64_t i : std::vector<std::int64_t>{5, 12, 19})
    EXPECT_EQ(v.cell_offsets[std::size_t(i) + 1], v.cell_offsets[std::size_t(i)]) << i;
  for (std::size_t j = 0; j < ids.size(); ++j) {
    const std::size_t i = std::size_t(ids[j]);
    ASSERT_EQ(v.cell_offsets[i + 1] - v.cell_offsets[i], f.cell_offsets[j + 1] - f.cell_offsets[j])
        << "point " << i;
  }
}

// The hull from the triangulation's boundary: counter-clockwise, only extreme points (the
// collinear boundary points of a grid are vertices of the triangulation, not of the hull), every
// point inside or on it (exact orientation).
TEST(Delaunay2d, ConvexHullVertices) {
  for (const char* d : {"grid", "circle", "uniform"}) {
    SCOPED_TRACE(d);
    const auto p = generate2d(d, 3000, 8);
    const double* xy = &p.data()->x;
    const auto t = delaunay2d(p, cpu());
    const auto v = convex_hull2d_vertices(xy, std::int64_t(p.size()), t.triangles.data(),
                                          t.neighbors.data(), t.num_triangles);
    const std::size_t h = v.size();
    ASSERT_GE(h, 3u);
    if (std::string(d) == "grid") EXPECT_EQ(h, 4u);
    for (std::size_t i = 0; i < h; ++i) {
      const Point2 a = p[std::size_t(v[i])], b = p[std::size_t(v[(i + 1) % h])],
                   c = p[std::size_t(v[(i + 2) % h])];
      EXPECT_GT(orient2d(a, b, c), 0) << "vertex not extreme or not counter-clockwise";
      for (std::size_t j = 0; j < p.size(); j += 7) EXPECT_GE(orient2d(a, b, p[j]), 0);
    }
  }
}

// Beyond 2^29 slots (2^28 points) neighbour pointers and work-list entries use bit 31 (the
// wide encoding, read as unsigned). The test switch numbers the slots from the top of that
// range down, so that small inputs go through it: every distribution and degenerate case then
// gives the arrays of slots numbered from 0, exactly (the output renumbers triangles).
TEST(Delaunay2d, TopOfTheWideSlotRange) {
  std::vector<gg_del2d::Case> cases = gg_del2d::degenerate_cases();
  for (auto& c : gg_del2d::distribution_cases({100, 20000}, 5)) cases.push_back(std::move(c));
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const auto ref = delaunay2d(c.pts, cpu());
    for (const bool batches : {false, true}) {  // (both schedules: one_by_one.inl's and the GPU's)
      const auto r = delaunay2d(c.pts, gg_test::tuned(cpu(), [&](detail::Tuning& t) {
                                  t.del2d.slot_base = std::int64_t(1)
                                                      << 30;  // clamped: 2^30 - 1 last
                                  t.del2d.batches = batches;
                                }));
      expect_valid(c.pts, r);
      EXPECT_EQ(r.triangles, ref.triangles);
      EXPECT_EQ(r.neighbors, ref.neighbors);
    }
  }
}

// The CPU executor's own schedule (points one by one by their cavities, the threads over chunks
// of the curve; which points wait for the end depends on timing) and the GPU's (batches and flip
// rounds, run here on the CPU executor): the same arrays, on every distribution and degenerate
// case and on any thread count, run after run (issue 53: the executors give the same output).
TEST(Delaunay2d, BothSchedulesGiveTheSameArrays) {
  std::vector<gg_del2d::Case> cases = gg_del2d::degenerate_cases();
  for (auto& c : gg_del2d::distribution_cases({100, 20000, 100000}, 41))
    cases.push_back(std::move(c));
  std::int64_t deferred = 0, flat = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const auto ref =
        delaunay2d(c.pts, gg_test::tuned(cpu(), [](detail::Tuning& t) { t.del2d.batches = true; }));
    expect_valid(c.pts, ref);
    EXPECT_EQ(ref.stats.cavity_insertions, 0);
    for (const int threads : {1, 2, 3, 8}) {
      SCOPED_TRACE(threads);
      Delaunay2dOptions o = cpu();
      o.threads = threads;
      const auto r = delaunay2d(c.pts, o);
      EXPECT_EQ(r.triangles, ref.triangles);
      EXPECT_EQ(r.neighbors, ref.neighbors);
      EXPECT_EQ(r.duplicate_of, ref.duplicate_of);
      EXPECT_EQ(r.stats.cavity_insertions, r.stats.distinct_points - 3);
      EXPECT_EQ(r.stats.batches, 0);
      deferred += r.stats.deferred_points;
      flat += r.stats.flat_triangles;
    }
  }
  EXPECT_GT(deferred, 0);  // (the threads met: the waiting points' path was taken)
  // (flat hull triangles were peeled after the cavities: the peel readies the rounds' arrays
  // itself, which the CPU schedule leaves untouched: TriStore::ready_rounds)
  EXPECT_GT(flat, 0);
}

// The device entry reads the caller's points where they are (no copy to normalise -0): on the
// degenerate inputs (-0 and +0 duplicates among them) the same arrays as the host entry.
TEST(Delaunay2d, DeviceEntryOnDegenerateInput) {
  for (const auto& c : gg_del2d::degenerate_cases()) {
    SCOPED_TRACE(c.name);
    const std::int64_t n = std::int64_t(c.pts.size());
    const auto ref = delaunay2d(c.pts, cpu());
    const auto dv = delaunay2d_device(&c.pts.data()->x, n, cpu());
    const std::int64_t nt = ref.num_triangles;
    ASSERT_EQ(dv.num_triangles, nt);
    EXPECT_EQ(dv.num_duplicates, ref.num_duplicates);
    EXPECT_EQ(gg_test::host_prefix(dv.triangles, 3 * nt), ref.triangles);
    EXPECT_EQ(gg_test::host_prefix(dv.neighbors, 3 * nt), ref.neighbors);
    EXPECT_EQ(gg_test::host_prefix(dv.duplicate_of, n), ref.duplicate_of);
  }
}

// The flip rounds past their capacities (the points a batch inserts, the flip log, the exact
// pass's list), forced small on small inputs as large inputs reach them. The log and the exact
// list never change the result: the same arrays. A smaller batch changes the order of the
// insertions: the same triangles, and with the log and the exact list forced too, the same
// arrays as with the batch alone. Each path must be taken somewhere.
TEST(Delaunay2d, PastTheRoundsCapacities) {
  std::vector<gg_del2d::Case> cases = gg_del2d::degenerate_cases();
  for (auto& c : gg_del2d::distribution_cases({100, 20000}, 5)) cases.push_back(std::move(c));
  std::map<std::string, std::int64_t> seen;
  auto run = [&](const gg_del2d::Case& c, const Capacities& f) {
    auto r = delaunay2d(c.pts, gg_test::tuned(cpu(), [&](detail::Tuning& t) {
                          t.del2d = f;
                          t.del2d.batches = true;
                        }));
    expect_valid(c.pts, r);
    for (const char* k : {"exact_rest_passes", "log_relocations", "split_flip_rounds"})
      seen[k] += r.stats.counter_map().at(k);
    return r;
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const auto ref = run(c, {});
    for (const Capacities f : {Capacities{0, 16, 0}, {0, 0, 3}, {0, 16, 2}}) {
      const auto r = run(c, f);
      EXPECT_EQ(r.triangles, ref.triangles) << f.log_records << "/" << f.exact_entries;
      EXPECT_EQ(r.neighbors, ref.neighbors) << f.log_records << "/" << f.exact_entries;
      EXPECT_EQ(r.stats.flips, ref.stats.flips);
    }
    const auto batch = run(c, {29, 0, 0});
    EXPECT_EQ(batch.triangles, ref.triangles);  // (the output's order is the triangles')
    EXPECT_EQ(batch.neighbors, ref.neighbors);
    const auto all = run(c, {29, 16, 2});
    EXPECT_EQ(all.triangles, batch.triangles);
    EXPECT_EQ(all.neighbors, batch.neighbors);
  }
  for (const auto& [k, v] : seen) EXPECT_GT(v, 0) << k;
}

// The flip rounds of short lists in one team of threads (flip_until_delaunay) or as kernels
// (Tuning::Del2d::team_list -1): the same arrays and the same rounds, whether the team takes
// every round it may (a list of any length, up to a round that needs a check: past the flip
// log's or the exact list's capacity, forced small, it hands the round back to the checked
// kernels), only lists of up to 3 entries, or none.
TEST(Delaunay2d, RoundsInATeamOrAsKernels) {
  std::vector<gg_del2d::Case> cases = gg_del2d::degenerate_cases();
  for (auto& c : gg_del2d::distribution_cases({100, 20000}, 9)) cases.push_back(std::move(c));
  const std::vector<Capacities> teams = {
      {0, 0, 0, 0, 1 << 30}, {0, 16, 2, 0, 1 << 30}, {0, 0, 0, 0, 3}, {0, 0, 0, 0, 0}};
  std::vector<std::int64_t> team_rounds(teams.size(), 0);
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    Capacities none;
    none.team_list = -1;
    const auto ref = delaunay2d(c.pts, gg_test::tuned(cpu(), [&](detail::Tuning& t) {
                                  t.del2d = none;
                                  t.del2d.batches = true;
                                }));
    EXPECT_EQ(ref.stats.team_flip_rounds, 0);
    for (std::size_t k = 0; k < teams.size(); ++k) {
      const Capacities& f = teams[k];
      SCOPED_TRACE(std::to_string(f.team_list) + " / " + std::to_string(f.log_records));
      const auto r = delaunay2d(c.pts, gg_test::tuned(cpu(), [&](detail::Tuning& t) {
                                  t.del2d = f;
                                  t.del2d.batches = true;
                                }));
      expect_valid(c.pts, r);
      EXPECT_EQ(r.triangles, ref.triangles);
      EXPECT_EQ(r.neighbors, ref.neighbors);
      EXPECT_EQ(r.stats.flips, ref.stats.flips);
      EXPECT_EQ(r.stats.flip_rounds, ref.stats.flip_rounds);
      EXPECT_LE(r.stats.team_flip_rounds, r.stats.flip_rounds);
      team_rounds[k] += r.stats.team_flip_rounds;
    }
  }
  for (std::size_t k = 0; k < teams.size(); ++k) EXPECT_GT(team_rounds[k], 0) << k;
}

// Point location into the caller's array: the same answers as into the library's, on any thread
// count; an array of another length, or the CUDA backend (there is no device point location),
// refused before anything is written.
TEST(Delaunay2d, PointLocationIntoTheCallersArray) {
  const auto pts = generate2d("uniform", 5000, 21);
  const auto t = delaunay2d(pts, cpu());
  std::vector<double> q;
  for (std::size_t i = 0; i + 1 < pts.size(); i += 3)
    q.insert(q.end(), {(pts[i].x + pts[i + 1].x) / 2, (pts[i].y + pts[i + 1].y) / 2});
  q.insert(q.end(), {-1.0, 0.5, 2.0, 2.0});  // outside the hull
  const std::int64_t m = std::int64_t(q.size() / 2);
  const auto own = find_simplex2d(&pts.data()->x, std::int64_t(pts.size()), t.triangles.data(),
                                  t.neighbors.data(), t.num_triangles, q.data(), m);
  ASSERT_EQ(std::int64_t(own.size()), m);
  EXPECT_EQ(own[std::size_t(m - 1)], -1);
  EXPECT_EQ(own[std::size_t(m - 2)], -1);
  for (int threads : {1, 2}) {
    std::vector<std::int32_t> mine(std::size_t(m), 7);
    LocateOptions o;
    o.threads = threads;
    o.into.simplices = {mine.data(), m};
    const auto r = find_simplex2d(&pts.data()->x, std::int64_t(pts.size()), t.triangles.data(),
                                  t.neighbors.data(), t.num_triangles, q.data(), m, o);
    EXPECT_TRUE(r.empty());
    EXPECT_EQ(mine, std::vector<std::int32_t>(own.begin(), own.end())) << threads;
  }
  std::vector<std::int32_t> short_one(std::size_t(m - 1), 7);
  LocateOptions bad;
  bad.into.simplices = {short_one.data(), m - 1};
  EXPECT_THROW(find_simplex2d(&pts.data()->x, std::int64_t(pts.size()), t.triangles.data(),
                              t.neighbors.data(), t.num_triangles, q.data(), m, bad),
               Error);
  EXPECT_EQ(short_one, std::vector<std::int32_t>(std::size_t(m - 1), 7));
  LocateOptions gpu;
  gpu.backend = Backend::Cuda;
  try {
    find_simplex2d(&pts.data()->x, std::int64_t(pts.size()), t.triangles.data(), t.neighbors.data(),
                   t.num_triangles, q.data(), m, gpu);
    ADD_FAILURE() << "CUDA point location accepted";
  } catch (const Error& e) {
    EXPECT_EQ(int(e.code()), int(ErrorCode::Unsupported));
  }
}

// The limit the header states: refused before any work, with the number.
TEST(Delaunay2d, PointLimitIsStated) {
  try {
    delaunay2d(static_cast<const double*>(nullptr), (std::int64_t(1) << 29) - 1, cpu());
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(int(e.code()), int(ErrorCode::InvalidInput));
    EXPECT_NE(std::string(e.what()).find("at most 536870910"), std::string::npos) << e.what();
  }
}

// DynamicDelaunay2d (issue 47): points added in chunks give, after every call, exactly the
// triangulation of a fresh call on the points so far; on every distribution and degenerate
// case, in random orders and chunk sizes.
TEST(DynamicDelaunay2d, SameAsFreshAfterEveryInsert) {
  std::uint64_t seed = 1;
  for (const auto& c : gg_del2d::degenerate_cases())
    for (int r = 0; r < 3; ++r) {
      SCOPED_TRACE(c.name + " order " + std::to_string(r));
      gg_del2d::follow_in_chunks(c, cpu(), seed++);
    }
  for (const auto& c : gg_del2d::distribution_cases({10, 1000, 20000}, 23)) {
    if (c.name.rfind("two_segments", 0) == 0 && c.pts.size() < 4) continue;
    SCOPED_TRACE(c.name);
    gg_del2d::follow_in_chunks(c, cpu(), seed++);
  }
}

// The same sequence of calls gives the same arrays, on any thread count.
TEST(DynamicDelaunay2d, SameArraysEveryRunAndThreadCount) {
  const auto pts = generate2d("uniform", 30000, 8);
  auto run = [&](int threads) {
    Delaunay2dOptions o = cpu();
    o.threads = threads;
    DynamicDelaunay2d d(&pts.data()->x, 10000, o);
    d.insert(&pts[10000].x, 5);
    d.insert(&pts[10005].x, 19995);
    return d.triangulation();
  };
  const auto a = run(1);
  for (int threads : {2, 0}) {
    const auto b = run(threads);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.neighbors, b.neighbors);
  }
}

// Copies of points already in it are not vertices and name the earliest copy; so do copies
// within one insertion.
TEST(DynamicDelaunay2d, DuplicatesOfEarlierPoints) {
  std::vector<Point2> pts = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  DynamicDelaunay2d d(&pts.data()->x, 4, cpu());
  const std::vector<Point2> more = {{1, 0}, {0.5, 0.5}, {-0.0, 0.0}, {0.5, 0.5}};
  d.insert(&more.data()->x, 4);
  pts.insert(pts.end(), more.begin(), more.end());
  const auto t = d.triangulation();
  expect_valid(pts, t);
  EXPECT_EQ(d.num_points(), 8);
  EXPECT_EQ(d.num_duplicates(), 3);
  const std::vector<std::int32_t> want = {-1, -1, -1, -1, 1, -1, 0, 5};
  EXPECT_EQ(std::vector<std::int32_t>(t.duplicate_of.begin(), t.duplicate_of.end()), want);
  d.insert(&more.data()->x, 0);  // nothing to add: nothing changes
  EXPECT_EQ(d.triangulation().triangles, t.triangles);
}

// A refused insertion (bad coordinates, too few points to start) leaves the object as it was,
// and it goes on working.
TEST(DynamicDelaunay2d, RefusedCallsLeaveItAsItWas) {
  const auto pts = generate2d("uniform", 2000, 9);
  DynamicDelaunay2d d(&pts.data()->x, 1000, cpu());
  const auto before = d.triangulation();
  std::vector<Point2> bad(pts.begin() + 1000, pts.begin() + 1010);
  bad[7].y = std::nan("");
  try {
    d.insert(&bad.data()->x, std::int64_t(bad.size()));
    ADD_FAILURE() << "NaN accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidInput);
  }
  EXPECT_THROW(d.insert(&bad.data()->x, -1), Error);
  EXPECT_EQ(d.num_points(), 1000);
  const auto after = d.triangulation();
  EXPECT_EQ(after.triangles, before.triangles);
  EXPECT_EQ(after.neighbors, before.neighbors);
  d.insert(&pts[1000].x, 1000);
  const std::vector<Point2> all(pts.begin(), pts.end());
  expect_valid(all, d.triangulation());
  // construction refusals
  const std::vector<Point2> line = {{0, 0}, {1, 1}, {2, 2}};
  EXPECT_THROW(DynamicDelaunay2d(&line.data()->x, 3, cpu()), Error);
  Delaunay2dOptions dig = cpu();
  dig.method = Method::Digital;
  EXPECT_THROW(DynamicDelaunay2d(&pts.data()->x, 100, dig), Error);
}

// The device entries on the CPU executor take host memory, as delaunay2d_device does.
TEST(DynamicDelaunay2d, DeviceEntriesOnTheCpuExecutor) {
  const auto pts = generate2d("gaussian", 5000, 10);
  auto d = DynamicDelaunay2d::from_device(&pts.data()->x, 3000, cpu());
  d.insert_device(&pts[3000].x, 2000);
  const auto dev = d.device_triangulation();
  ASSERT_EQ(dev.backend, Backend::Cpu);
  const auto host = d.triangulation();
  ASSERT_EQ(dev.num_triangles, host.num_triangles);
  EXPECT_TRUE(std::equal(host.triangles.begin(), host.triangles.end(), dev.triangles.get()));
  EXPECT_TRUE(std::equal(host.neighbors.begin(), host.neighbors.end(), dev.neighbors.get()));
  expect_valid(pts, host);
}

// DynamicDelaunay2d::move (issue 47): after any displacement the triangulation of a fresh call
// on the moved points. Small moves repair the kept triangulation (counter move_rebuilt 0); moves
// that fold it, or make points coincide or part, build afresh; grids moved onto exact grids
// (every square cocircular again) and points moved onto others are included.
TEST(DynamicDelaunay2d, MoveGivesTheFreshTriangulation) {
  std::mt19937_64 rng(31);
  std::int64_t repaired = 0, reinserted = 0, rebuilt = 0;
  auto check = [&](DynamicDelaunay2d& d, const std::vector<Point2>& q, const char* what) {
    SCOPED_TRACE(what);
    d.move(&q.data()->x, std::int64_t(q.size()));
    const auto t = d.triangulation();
    expect_valid(q, t);
    const auto fresh = delaunay2d(q, cpu());
    EXPECT_EQ(t.triangles, fresh.triangles);
    EXPECT_EQ(t.neighbors, fresh.neighbors);
    EXPECT_EQ(t.duplicate_of, fresh.duplicate_of);
    const Delaunay2dStats& c = d.stats();
    (c.move_rebuilt ? rebuilt : c.move_reinserted ? reinserted : repaired)++;
  };
  auto cases = gg_del2d::degenerate_cases();
  for (const auto& c : gg_del2d::distribution_cases({1000, 20000}, 37)) cases.push_back(c);
  for (const auto& c : cases) {
    if (c.name.rfind("two_segments", 0) == 0) continue;
    SCOPED_TRACE(c.name);
    const std::vector<Point2>& p = c.pts;
    DynamicDelaunay2d d(&p.data()->x, std::int64_t(p.size()), cpu());
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const auto& x : p) {
      lo[0] = std::min(lo[0], x.x), hi[0] = std::max(hi[0], x.x);
      lo[1] = std::min(lo[1], x.y), hi[1] = std::max(hi[1], x.y);
    }
    const double spacing = std::sqrt((hi[0] - lo[0]) * (hi[1] - lo[1]) / double(p.size())) + 1e-300;
    auto jitter = [&](double f) {
      std::normal_distribution<double> N(0, f * spacing);
      std::vector<Point2> q = p;
      for (auto& x : q) x.x += N(rng), x.y += N(rng);
      return q;
    };
    check(d, jitter(1e-3), "moved by 1e-3 of the spacing");
    check(d, jitter(0.3), "moved by 0.3 of the spacing");
    check(d, p, "moved back (degenerate again)");
    std::vector<Point2> q = p;
    q[q.size() / 3].x = p[0].x + spacing / 3;  // one point far, beside another
    q[q.size() / 3].y = p[0].y + spacing / 5;
    check(d, q, "one point far");
    check(d, p, "and back");
    q = p;
    q[q.size() / 2] = q[0];  // one point onto another
    check(d, q, "a point onto another");
    check(d, p, "and apart again");
    q = p;
    std::shuffle(q.begin(), q.end(), rng);  // everything scrambled
    check(d, q, "scrambled");
  }
  // Every path ran: the repair in place (tiny moves), the repair with the vertices of
  // turned-over triangles taken out and put back, and the rebuild (points that now coincide).
  std::printf("moves: %lld repaired, %lld with vertices put back, %lld rebuilt\n",
              (long long)repaired, (long long)reinserted, (long long)rebuilt);
  EXPECT_GE(repaired, 5);
  EXPECT_GE(reinserted, 10);
  EXPECT_GE(rebuilt, 5);
}

// A move with another count, or bad coordinates, is refused and leaves the object as it was.
TEST(DynamicDelaunay2d, RefusedMoveLeavesItAsItWas) {
  auto p = generate2d("uniform", 3000, 4);
  DynamicDelaunay2d d(&p.data()->x, 3000, cpu());
  const auto before = d.triangulation();
  EXPECT_THROW(d.move(&p.data()->x, 2999), Error);
  p[5].x = std::numeric_limits<double>::infinity();
  EXPECT_THROW(d.move(&p.data()->x, 3000), Error);
  EXPECT_EQ(d.triangulation().triangles, before.triangles);
}

// insert, move and remove in random sequences (issue 47): after every call the triangulation of
// a fresh call on the points left, on every distribution and degenerate case.
TEST(DynamicDelaunay2d, RandomOperationsGiveTheFreshTriangulation) {
  auto cases = gg_del2d::degenerate_cases();
  for (const auto& c : gg_del2d::distribution_cases({50, 5000}, 41))
    if (c.name.rfind("two_segments", 0) != 0) cases.push_back(c);
  gg_test::random_operations<gg_del2d::Kept2d>(cases, cpu(), 300, 3, 10);
}

// changes() (issue 47): gg_test::changes_need_tracking.
TEST(DynamicDelaunay2d, ChangesNeedTracking) {
  gg_test::changes_need_tracking<gg_del2d::Kept2d>(generate2d("uniform", 3000, 45), cpu());
}

// A removed point is no vertex and keeps its index (kRemovedPoint); a copy of it, given before
// or after, is a vertex in its place. Bad index lists are refused and change nothing.
TEST(DynamicDelaunay2d, RemovedPointsAndRefusals) {
  auto p = generate2d("uniform", 2000, 44);
  p.push_back(p[10]);  // 2000: a copy of point 10
  DynamicDelaunay2d d(&p.data()->x, std::int64_t(p.size()), cpu());
  EXPECT_EQ(d.num_duplicates(), 1);
  const std::int32_t r[] = {10, 20};
  d.remove(r, 2);
  auto t = d.triangulation();
  EXPECT_EQ(d.num_removed(), 2);
  EXPECT_EQ(d.num_duplicates(), 0);
  EXPECT_EQ(t.duplicate_of[10], kRemovedPoint);
  EXPECT_EQ(t.duplicate_of[20], kRemovedPoint);
  EXPECT_EQ(t.duplicate_of[2000], -1);  // the copy took point 10's place
  for (std::int32_t v : t.triangles) EXPECT_TRUE(v != 10 && v != 20);
  d.insert(&p[20].x, 1);  // point 20's coordinates again: a new vertex, 2001
  t = d.triangulation();
  EXPECT_EQ(t.duplicate_of[2001], -1);
  EXPECT_NE(std::find(t.triangles.begin(), t.triangles.end(), 2001), t.triangles.end());
  const auto before = d.triangulation();
  auto refused = [&](std::vector<std::int32_t> idx, ErrorCode code) {
    try {
      d.remove(idx.data(), std::int64_t(idx.size()));
      ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), code) << e.what();
    }
    EXPECT_EQ(d.num_removed(), 2);
    EXPECT_EQ(d.triangulation().triangles, before.triangles);
  };
  refused({5, 2002}, ErrorCode::InvalidArgument);  // out of range
  refused({5, -1}, ErrorCode::InvalidArgument);
  refused({5, 6, 5}, ErrorCode::InvalidArgument);  // twice
  refused({7, 10}, ErrorCode::InvalidArgument);    // removed before
  std::vector<std::int32_t> all;
  for (std::int32_t i = 0; i < 2002; ++i)
    if (i != 10 && i != 20 && i != 0 && i != 1) all.push_back(i);
  refused(all, ErrorCode::DegenerateInput);  // 2 points left
  d.remove(nullptr, 0);                      // nothing
  EXPECT_EQ(d.num_removed(), 2);
}
