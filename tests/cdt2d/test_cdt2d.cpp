// The constrained Delaunay triangulation on the CPU executor: random planar straight-line graphs,
// grids, thin polygons and cocircular points against the exact checker; segments through
// points, repeated and zero-length segments, duplicates; crossing segments refused by name.
#include <gtest/gtest.h>

#include <cstdio>

#include "../common/caller_arrays.hpp"
#include "cdt2d_cases.hpp"
#include "gpugeom/delaunay2d.hpp"

using namespace gpugeom;

namespace {
ConstrainedTriangulation2d run(const gg_cdt::Pslg& g, Backend b = Backend::Cpu) {
  Cdt2dOptions o;
  o.backend = b;
  return cdt2d(g.xy.data(), std::int64_t(g.xy.size() / 2), g.segs.data(),
               std::int64_t(g.segs.size() / 2), o);
}
}  // namespace

TEST(Cdt2d, RandomPslgs) {
  for (unsigned seed : {1u, 2u, 3u})
    for (std::int64_t n : {50, 2000}) {
      const auto g = gg_cdt::random_pslg(n, n / 2, seed);
      const auto r = run(g);
      gg_cdt::expect_cdt(g, r);
      EXPECT_GT(r.stats.segments_recovered, 0) << g.name;
      EXPECT_EQ(r.stats.segments_present + r.stats.segments_recovered + r.repeated_segments +
                    r.zero_length_segments,
                std::int64_t(g.segs.size() / 2))
          << g.name;
    }
}

// Long segments cross many triangles: large cavities, and cavities whose polygons have antennas
// (an edge off the segment with both its triangles crossed). Every result is exact, and the same
// on one thread as on several (the rounds never depend on timing).
TEST(Cdt2d, LongSegmentsAndThreadCounts) {
  std::int64_t antennas = 0;
  for (unsigned seed = 1; seed <= 12; ++seed)
    for (std::int64_t n : {40, 400, 4000}) {
      const auto g = gg_cdt::random_pslg(n, n / 4, seed, seed % 3 == 0 ? 2 : 1);
      const auto r = run(g);
      gg_cdt::expect_cdt(g, r);
      Cdt2dOptions o;
      o.backend = Backend::Cpu;
      o.threads = 1;
      const auto one = cdt2d(g.xy.data(), n, g.segs.data(), std::int64_t(g.segs.size() / 2), o);
      EXPECT_EQ(one.triangles, r.triangles) << g.name;
      EXPECT_EQ(one.neighbors, r.neighbors) << g.name;
      EXPECT_EQ(one.segment_of, r.segment_of) << g.name;
      EXPECT_GT(r.stats.cavity_triangles, 0) << g.name;
      antennas += r.stats.cavity_antennas;
    }
  EXPECT_GT(antennas, 0);  // (the cases exercise them)
  std::printf("antenna edges met: %lld\n", static_cast<long long>(antennas));
}

// Terrain-like contour lines, every edge a segment, with points between them.
TEST(Cdt2d, ContourLines) {
  for (const auto& g : {gg_cdt::contour_pslg(5, 60, 200, 1), gg_cdt::contour_pslg(20, 400, 3000, 2),
                        gg_cdt::contour_pslg(3, 2000, 100, 3)}) {
    const auto r = run(g);
    gg_cdt::expect_cdt(g, r);
    EXPECT_EQ(r.stats.segments_present + r.stats.segments_recovered,
              std::int64_t(g.segs.size() / 2))
        << g.name;
  }
}

TEST(Cdt2d, DegenerateLayouts) {
  for (const auto& g : {gg_cdt::grid_pslg(9), gg_cdt::grid_pslg(16), gg_cdt::thin_polygon(40),
                        gg_cdt::circle_pslg(64, 5)}) {
    const auto r = run(g);
    gg_cdt::expect_cdt(g, r);
  }
  // A segment through collinear points is the chain of edges between them.
  const auto t = gg_cdt::thin_polygon(40);
  const auto r = run(t);
  EXPECT_GT(r.repeated_segments + r.stats.segment_pieces, 0);
}

// Every Delaunay edge given as a segment: nothing to flip.
TEST(Cdt2d, DelaunayEdgesNeedNoFlips) {
  gg_cdt::Pslg g = gg_cdt::random_pslg(500, 0, 9);
  const auto dt = delaunay2d(g.xy.data(), 500);
  for (std::size_t i = 0; i < dt.triangles.size(); ++i)
    if (dt.neighbors[i] < std::int32_t(i / 3))  // each edge once (hull edges too)
      g.segs.insert(g.segs.end(), {dt.triangles[i - i % 3 + (i % 3 + 1) % 3],
                                   dt.triangles[i - i % 3 + (i % 3 + 2) % 3]});
  const auto r = run(g);
  gg_cdt::expect_cdt(g, r);
  EXPECT_EQ(r.stats.segments_recovered, 0);
  EXPECT_EQ(r.stats.cavity_triangles, 0);
  EXPECT_EQ(r.stats.recovery_rounds, 0);
  EXPECT_EQ(r.triangles, dt.triangles);
}

TEST(Cdt2d, RepeatedZeroLengthAndDuplicatePoints) {
  gg_cdt::Pslg g = gg_cdt::random_pslg(300, 100, 4);
  const std::int32_t n = 300;
  g.xy.insert(g.xy.end(), {g.xy[0], g.xy[1]});  // point n repeats point 0
  const std::size_t kept = g.segs.size() / 2;
  g.segs.insert(g.segs.end(), {5, 5, n, 0, g.segs[1], g.segs[0], n, 7});
  const auto r = run(g);
  gg_cdt::expect_cdt(g, r);
  EXPECT_EQ(r.zero_length_segments, 2);  // 5-5 and n-0 (n repeats 0)
  EXPECT_EQ(r.num_duplicates, 1);
  EXPECT_EQ(r.duplicate_of[n], 0);
  // the reversed first segment repeats it; n-7 is 0-7 (a repeat if 0-7 was given)
  EXPECT_GE(r.repeated_segments, 1);
  EXPECT_EQ(r.stats.segments, std::int64_t(kept) + 4);
}

TEST(Cdt2d, CrossingSegmentsAreNamed) {
  const std::vector<double> xy{0, 0, 2, 2, 0, 2, 2, 0, 1, 3, 3, 1};
  const std::vector<std::int32_t> segs{4, 5, 0, 1, 2, 3};  // 1 and 2 cross at (1, 1)
  try {
    cdt2d(xy.data(), 6, segs.data(), 3);
    ADD_FAILURE() << "crossing segments were accepted";
  } catch (const Error& e) {
    EXPECT_EQ(int(e.code()), int(ErrorCode::InvalidInput));
    EXPECT_NE(std::string(e.what()).find("segments 1 and 2 cross"), std::string::npos) << e.what();
  }
  const std::vector<std::int32_t> bad{0, 6};
  EXPECT_THROW(cdt2d(xy.data(), 6, bad.data(), 1), Error);
  // Crossing at an input point is fine: both run through it.
  const std::vector<double> xy2{0, 0, 2, 2, 0, 2, 2, 0, 1, 1};
  const std::vector<std::int32_t> segs2{0, 1, 2, 3};
  const gg_cdt::Pslg g{"cross at a point", xy2, segs2};
  const auto r = run(g);
  gg_cdt::expect_cdt(g, r);
  EXPECT_EQ(r.stats.segment_pieces, 4);
}

ConstrainedTriangulation2d run_split(const gg_cdt::Pslg& g, Backend b = Backend::Cpu) {
  Cdt2dOptions o;
  o.backend = b;
  o.crossings = Cdt2dOptions::Crossings::Split;
  return cdt2d(g.xy.data(), std::int64_t(g.xy.size() / 2), g.segs.data(),
               std::int64_t(g.segs.size() / 2), o);
}

// Crossings::Split: a new vertex where two segments cross, reported with both; a grid of long
// lines (crossings exactly representable: one vertex each, three lines through one point give
// one vertex); random segments that cross anywhere (rounded intersections, segments crossing
// many others); crossings exactly at input points add nothing.
TEST(Cdt2d, CrossingSegmentsSplit) {
  {
    const gg_cdt::Pslg g{"x", {0, 0, 2, 2, 0, 2, 2, 0, 1, 3, 3, 1}, {4, 5, 0, 1, 2, 3}};
    const auto r = run_split(g);
    gg_cdt::expect_split_cdt(g, r);
    ASSERT_EQ(r.new_points.size(), 2u);
    EXPECT_EQ(r.new_points[0], 1.0);
    EXPECT_EQ(r.new_points[1], 1.0);
    EXPECT_EQ(r.new_point_segments, (std::vector<std::int32_t>{1, 2}));
    EXPECT_EQ(r.stats.crossings, 1);
    EXPECT_EQ(r.stats.segments_split, 2);
  }
  {
    gg_cdt::Pslg g{"line grid", {}, {}};
    auto add = [&](double x, double y) {
      g.xy.insert(g.xy.end(), {x, y});
      return std::int32_t(g.xy.size() / 2 - 1);
    };
    for (int i = 0; i < 10; ++i) {
      g.segs.insert(g.segs.end(), {add(-1, i + 0.5), add(11, i + 0.5)});  // rows
      g.segs.insert(g.segs.end(), {add(i + 0.5, -1), add(i + 0.5, 11)});  // columns
    }
    g.segs.insert(g.segs.end(), {add(-1.5, -1.5), add(11.5, 11.5)});  // through (k.5, k.5)
    for (int i = 0; i < 200; ++i) add(0.37 + 0.049 * i, 0.11 + 0.0517 * (i % 190));
    const auto r = run_split(g);
    gg_cdt::expect_split_cdt(g, r);
    EXPECT_EQ(r.stats.crossings, 100);  // the diagonal's 10 are among them
    EXPECT_EQ(r.stats.segments_split, 21);
    // Refused without the option, naming two of the lines.
    EXPECT_THROW(run(g), Error);
  }
  for (unsigned seed : {1u, 2u, 3u})
    for (std::int64_t n : {30, 600, 3000}) {
      const auto g = gg_cdt::crossing_pslg(n, n / 6, seed);
      const auto r = run_split(g);
      gg_cdt::expect_split_cdt(g, r);
      EXPECT_GT(r.stats.crossings, 0) << g.name;
    }
  {
    // Two segments crossing exactly at an input point: nothing to add.
    const gg_cdt::Pslg g{"at a point", {0, 0, 2, 2, 0, 2, 2, 0, 1, 1}, {0, 1, 2, 3}};
    const auto r = run_split(g);
    gg_cdt::expect_split_cdt(g, r);
    EXPECT_TRUE(r.new_points.empty());
  }
}

// The device entry on the CPU executor (its "device" memory is host memory): the same arrays as
// the host entry, with and without a domain; bad indices, crossings and Split refused.
TEST(Cdt2d, DeviceEntryOnTheCpu) {
  const auto g = gg_cdt::contour_pslg(8, 500, 2000, 3);
  const std::int64_t n = std::int64_t(g.xy.size() / 2), m = std::int64_t(g.segs.size() / 2);
  for (bool enclosed : {false, true}) {
    Cdt2dOptions o;
    o.backend = Backend::Cpu;
    if (enclosed) {
      o.domain = Cdt2dOptions::Domain::Enclosed;
      o.regions = {{0.0, 0.5, 3.0}};
    }
    const auto h = cdt2d(g.xy.data(), n, g.segs.data(), m, o);
    const auto d = cdt2d_device(g.xy.data(), n, g.segs.data(), m, o);
    ASSERT_EQ(d.num_triangles, h.num_triangles);
    EXPECT_EQ(d.backend, Backend::Cpu);
    const std::size_t k = 3 * std::size_t(d.num_triangles);
    EXPECT_EQ(std::vector<std::int32_t>(d.triangles.get(), d.triangles.get() + k), h.triangles);
    EXPECT_EQ(std::vector<std::int32_t>(d.neighbors.get(), d.neighbors.get() + k), h.neighbors);
    EXPECT_EQ(std::vector<std::int32_t>(d.segment_of.get(), d.segment_of.get() + k), h.segment_of);
    EXPECT_EQ(std::vector<std::int32_t>(d.duplicate_of.get(), d.duplicate_of.get() + n),
              h.duplicate_of);
    EXPECT_EQ(d.removed_triangles, h.removed_triangles);
    if (enclosed) {
      ASSERT_TRUE(d.attribute);
      EXPECT_EQ(std::vector<double>(d.attribute.get(), d.attribute.get() + d.num_triangles),
                h.attribute);
    }
    EXPECT_EQ(d.stats.segments_recovered, h.stats.segments_recovered);
  }
  Cdt2dOptions o;
  o.backend = Backend::Cpu;
  std::vector<std::int32_t> bad = g.segs;
  bad[7] = std::int32_t(n);
  try {
    cdt2d_device(g.xy.data(), n, bad.data(), m, o);
    ADD_FAILURE() << "a bad index was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(int(e.code()), int(ErrorCode::InvalidInput));
    EXPECT_NE(std::string(e.what()).find("segment 3 names point"), std::string::npos) << e.what();
  }
  const std::vector<double> xy{0, 0, 2, 2, 0, 2, 2, 0};
  const std::vector<std::int32_t> x{0, 1, 2, 3};
  EXPECT_THROW(cdt2d_device(xy.data(), 4, x.data(), 2, o), Error);
  o.crossings = Cdt2dOptions::Crossings::Split;
  EXPECT_THROW(cdt2d_device(xy.data(), 4, x.data(), 2, o), Error);
}

// Into the caller's arrays (Cdt2dOptions::into), from both entries: the same arrays as the
// library's, the result's own left empty; an array too short refused once the count is known,
// with nothing written anywhere; Crossings::Split refuses them.
TEST(Cdt2d, IntoCallersArrays) {
  using gg_test::CallerArray;
  const auto g = gg_cdt::contour_pslg(8, 500, 2000, 3);
  const std::int64_t n = std::int64_t(g.xy.size() / 2), m = std::int64_t(g.segs.size() / 2);
  Cdt2dOptions o;
  o.backend = Backend::Cpu;
  o.domain = Cdt2dOptions::Domain::Enclosed;
  o.regions = {{0.0, 0.5, 3.0}};
  const auto ref = cdt2d(g.xy.data(), n, g.segs.data(), m, o);
  const std::int64_t nt = ref.num_triangles, cap = 3 * delaunay2d_max_triangles(n);
  ASSERT_GT(nt, 0);
  for (bool device : {false, true}) {
    SCOPED_TRACE(device ? "device entry" : "host entry");
    CallerArray<std::int32_t> t(cap, 7), nb(cap, 7), sg(cap, 7), dup(n, 7);
    CallerArray<double> at(cap / 3, 7);
    auto mine = o;
    mine.into = {t.buf(), nb.buf(), sg.buf(), dup.buf(), at.buf()};
    std::int64_t count = 0;
    if (device) {
      const auto r = cdt2d_device(g.xy.data(), n, g.segs.data(), m, mine);
      EXPECT_FALSE(r.triangles || r.neighbors || r.segment_of || r.duplicate_of || r.attribute);
      count = r.num_triangles;
    } else {
      const auto r = cdt2d(g.xy.data(), n, g.segs.data(), m, mine);
      EXPECT_TRUE(r.triangles.empty() && r.neighbors.empty() && r.segment_of.empty() &&
                  r.duplicate_of.empty() && r.attribute.empty());
      EXPECT_EQ(r.removed_triangles, ref.removed_triangles);
      count = r.num_triangles;
    }
    ASSERT_EQ(count, nt);
    EXPECT_EQ(gg_test::host_prefix(t.v.data(), 3 * nt), ref.triangles);
    EXPECT_EQ(gg_test::host_prefix(nb.v.data(), 3 * nt), ref.neighbors);
    EXPECT_EQ(gg_test::host_prefix(sg.v.data(), 3 * nt), ref.segment_of);
    EXPECT_EQ(gg_test::host_prefix(at.v.data(), nt), ref.attribute);
    EXPECT_EQ(dup.v, ref.duplicate_of);
    // One array too short: refused, and nothing written.
    CallerArray<std::int32_t> t2(cap, 7), sg2(3 * nt - 1, 7);
    mine.into = {t2.buf(), {}, sg2.buf(), {}, {}};
    gg_test::expect_refused(
        [&] {
          device ? (void)cdt2d_device(g.xy.data(), n, g.segs.data(), m, mine)
                 : (void)cdt2d(g.xy.data(), n, g.segs.data(), m, mine);
        },
        "into.segment_of holds " + std::to_string(3 * nt - 1) +
            " elements; this result needs at least " + std::to_string(3 * nt));
    EXPECT_TRUE(t2.untouched(7) && sg2.untouched(7));
  }
  auto split = o;
  split.crossings = Cdt2dOptions::Crossings::Split;
  CallerArray<std::int32_t> t(cap, 7);
  split.into.triangles = t.buf();
  gg_test::expect_refused([&] { (void)cdt2d(g.xy.data(), n, g.segs.data(), m, split); },
                          "Crossings::Split");
  EXPECT_TRUE(t.untouched(7));
}

// An L-shaped domain (its hull a pentagon of area 87.5, the L 75) with a 2x2 square hole and a
// divider, on every integer point of the L but the hole's centre: the kept triangles' areas
// (exact: half-integers) for each domain rule, holes and regions; the boundary of an enclosed
// domain is made of segments; neighbours stay symmetric.
TEST(Cdt2d, HolesOutsideAndRegions) {
  std::vector<double> xy;
  auto id = [&](double x, double y) {
    for (std::size_t i = 0; i < xy.size(); i += 2)
      if (xy[i] == x && xy[i + 1] == y) return std::int32_t(i / 2);
    ADD_FAILURE() << "no point " << x << "," << y;
    return std::int32_t(0);
  };
  for (int y = 0; y <= 10; ++y)
    for (int x = 0; x <= 10; ++x)
      if ((y <= 5 || x <= 5) && !(x == 3 && y == 2)) xy.insert(xy.end(), {double(x), double(y)});
  const double L[] = {0, 0, 10, 0, 10, 5, 5, 5, 5, 10, 0, 10}, H[] = {2, 1, 4, 1, 4, 3, 2, 3};
  std::vector<std::int32_t> segs;
  for (int k = 0; k < 6; ++k)
    segs.insert(segs.end(),
                {id(L[2 * k], L[2 * k + 1]), id(L[(2 * k + 2) % 12], L[(2 * k + 3) % 12])});
  for (int k = 0; k < 4; ++k)
    segs.insert(segs.end(),
                {id(H[2 * k], H[2 * k + 1]), id(H[(2 * k + 2) % 8], H[(2 * k + 3) % 8])});
  segs.insert(segs.end(), {id(5, 0), id(5, 5)});  // the divider
  const std::int64_t n = std::int64_t(xy.size() / 2), m = std::int64_t(segs.size() / 2);
  auto area = [&](const ConstrainedTriangulation2d& r, double attr, bool any) {
    double a = 0;
    for (std::size_t t = 0; t < r.num_triangles; ++t) {
      if (!any && r.attribute[t] != attr) continue;
      const double* p = &xy[2 * r.triangles[3 * t]];
      const double* q = &xy[2 * r.triangles[3 * t + 1]];
      const double* s = &xy[2 * r.triangles[3 * t + 2]];
      a += ((q[0] - p[0]) * (s[1] - p[1]) - (q[1] - p[1]) * (s[0] - p[0])) / 2;
    }
    return a;
  };
  auto check = [&](const ConstrainedTriangulation2d& r, bool enclosed, const std::string& what) {
    for (std::size_t i = 0; i < r.neighbors.size(); ++i) {
      const std::int32_t o = r.neighbors[i];
      if (o < 0) {
        if (enclosed) EXPECT_GE(r.segment_of[i], 0) << what << ": a boundary edge on no segment";
        continue;
      }
      int back = 0;
      for (int k = 0; k < 3; ++k)
        back += r.neighbors[3 * std::size_t(o) + k] == std::int32_t(i / 3);
      EXPECT_EQ(back, 1) << what << ": neighbours not symmetric at triangle " << i / 3;
    }
  };
  using Domain = Cdt2dOptions::Domain;
  struct Case {
    Domain domain;
    bool hole;
    double area;
  };
  for (const Case& c : {Case{Domain::ConvexHull, false, 87.5}, Case{Domain::Enclosed, false, 75},
                        Case{Domain::Enclosed, true, 71}, Case{Domain::ConvexHull, true, 83.5}}) {
    Cdt2dOptions o;
    o.backend = Backend::Cpu;
    o.domain = c.domain;
    if (c.hole) o.holes = {{3, 2}, {-5, -5}};  // (a point outside the hull removes nothing)
    const auto r = cdt2d(xy.data(), n, segs.data(), m, o);
    const std::string what = std::string(c.domain == Domain::Enclosed ? "enclosed" : "hull") +
                             (c.hole ? " with hole" : "");
    EXPECT_EQ(area(r, 0, true), c.area) << what;
    EXPECT_EQ(r.removed_triangles > 0, c.area < 87.5) << what;
    EXPECT_TRUE(r.attribute.empty());
    check(r, c.domain == Domain::Enclosed, what);
  }
  Cdt2dOptions o;
  o.backend = Backend::Cpu;
  o.domain = Domain::Enclosed;
  o.holes = {{3, 2}};
  o.regions = {{1, 8, 7.0}, {8, 2, 9.0}, {1.5, 9.5, 4.0}};  // the third lies in the first's part
  const auto r = cdt2d(xy.data(), n, segs.data(), m, o);
  ASSERT_EQ(r.attribute.size(), r.num_triangles);
  EXPECT_EQ(area(r, 7.0, false), 46);
  EXPECT_EQ(area(r, 9.0, false), 25);
  EXPECT_EQ(area(r, 4.0, false), 0);
  check(r, true, "regions");
}

#ifdef GG_HAVE_CGAL
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <array>

#include "../delaunay2d/del2d_cases.hpp"

// Points in general position: the constrained Delaunay triangulation is unique, so the triangle
// sets must equal CGAL's Constrained_Delaunay_triangulation_2 (random PSLGs, exact predicates).
TEST(Cdt2d, SameAsCgal) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, K>;
  using Fb = CGAL::Constrained_triangulation_face_base_2<K>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
  using CDT = CGAL::Constrained_Delaunay_triangulation_2<
      K, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;
  for (unsigned seed : {11u, 12u})
    for (std::int64_t n : {100, 5000}) {
      const auto g = gg_cdt::random_pslg(n, n / 3, seed);
      SCOPED_TRACE(g.name);
      CDT cdt;
      std::vector<CDT::Vertex_handle> vh(static_cast<std::size_t>(n));
      for (std::int64_t i = 0; i < n; ++i) {
        vh[std::size_t(i)] = cdt.insert(K::Point_2(g.xy[2 * i], g.xy[2 * i + 1]));
        vh[std::size_t(i)]->info() = std::int32_t(i);
      }
      for (std::size_t s = 0; s < g.segs.size(); s += 2)
        cdt.insert_constraint(vh[std::size_t(g.segs[s])], vh[std::size_t(g.segs[s + 1])]);
      std::vector<std::int32_t> faces;
      for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
        for (int k = 0; k < 3; ++k) faces.push_back(f->vertex(k)->info());
      const auto r = run(g);
      const auto ref = gg_del2d::triangle_set(faces.data(), faces.size() / 3);
      const auto got = gg_del2d::triangle_set(r.triangles.data(), r.num_triangles);
      EXPECT_EQ(got, ref);
    }
}
#endif
