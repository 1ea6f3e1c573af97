// Delaunay refinement on the CPU executor: Triangle's classic domains, small input angles,
// random PSLGs, regions and sizing, the Steiner limit, thread counts and bad options; every mesh
// judged by the exact checker with the bounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "../common/caller_arrays.hpp"
#include "refine2d_cases.hpp"

using namespace gpugeom;
using gg_refine::Domain;

namespace {
Refine2dOptions options(double angle, double area = 0) {
  Refine2dOptions o;
  o.backend = Backend::Cpu;
  o.min_angle = angle;
  o.max_area = area;
  return o;
}
}  // namespace

TEST(Refine2d, ClassicDomains) {
  for (const Domain& d : {gg_refine::square_with_hole(), gg_refine::letter_a()})
    for (double angle : {20.0, 30.0, 33.8})
      for (double area : {0.0, 0.01, 0.0005}) {
        const auto o = options(angle, area);
        const auto r = gg_refine::refine(d, o);
        SCOPED_TRACE(d.g.name + " angle " + std::to_string(angle) + " area " +
                     std::to_string(area));
        gg_refine::expect_quality(d, r, o);
        EXPECT_TRUE(r.small_angles.empty());
        EXPECT_TRUE(r.large_triangles.empty());
        if (area > 0 || angle > 30) EXPECT_GT(r.stats.steiner_points, 0);
      }
}

TEST(Refine2d, SmallInputAngles) {
  const Domain d = gg_refine::small_angles();
  for (double angle : {20.0, 30.0}) {
    const auto o = options(angle, 0.01);
    const auto r = gg_refine::refine(d, o);
    gg_refine::expect_quality(d, r, o);
    // Only the corner's triangles keep small angles, each for an input angle or a shell.
    EXPECT_FALSE(r.small_angles.empty());
    for (auto why : r.small_angle_reasons) EXPECT_NE(why, std::int8_t(SmallAngle::Limit));
  }
}

TEST(Refine2d, CoastlineAndRandomPslgs) {
  const Domain c = gg_refine::coastline(400);
  const auto o = options(28, 0.002);
  gg_refine::expect_quality(c, gg_refine::refine(c, o), o);
  for (unsigned seed : {1u, 2u}) {
    const Domain d = gg_refine::random_domain(300, seed);
    const auto o2 = options(25);
    const auto r = gg_refine::refine(d, o2);
    gg_refine::expect_quality(d, r, o2);
    for (auto v : r.segment_of) EXPECT_GE(v, RefinedMesh2d::kHullSegment);
  }
}

// The same arrays on one thread and on all, and from the device entry on the CPU executor.
TEST(Refine2d, ThreadCountsAndDeviceEntry) {
  const Domain d = gg_refine::letter_a();
  auto o = options(30, 2e-4);
  o.threads = 1;
  const auto one = gg_refine::refine(d, o);
  o.threads = 0;
  const auto all = gg_refine::refine(d, o);
  EXPECT_EQ(one.points, all.points);
  EXPECT_EQ(one.triangles, all.triangles);
  EXPECT_EQ(one.segment_of, all.segment_of);
  o.domain = Cdt2dOptions::Domain::Enclosed;
  o.holes = d.holes;
  const auto dev = refine2d_device(d.g.xy.data(), std::int64_t(d.g.xy.size() / 2), d.g.segs.data(),
                                   std::int64_t(d.g.segs.size() / 2), o);
  ASSERT_EQ(dev.backend, Backend::Cpu);
  ASSERT_EQ(dev.num_triangles, all.num_triangles);
  EXPECT_TRUE(std::equal(all.triangles.begin(), all.triangles.end(), dev.triangles.get()));
  EXPECT_TRUE(std::equal(all.points.begin(), all.points.end(), dev.points.get()));
}

// Degenerate input for the kept triangulation's flips: free points on a grid and on a circle
// inside a square (many exact co-circular quadruples, where a flip must not be done), refined
// to bounds; the same arrays on one thread and on all.
TEST(Refine2d, CocircularAndGridPoints) {
  Domain d{{"grid and circle", {}, {}}, {}, true};
  gg_refine::polygon(d.g, {-1, -1, 1, -1, 1, 1, -1, 1});
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j) d.g.xy.insert(d.g.xy.end(), {0.2 * i, 0.2 * j});
  for (int k = 0; k < 32; ++k) {
    const double a = k * 3.141592653589793 / 16;
    d.g.xy.insert(d.g.xy.end(), {0.93 * std::cos(a), 0.93 * std::sin(a)});
  }
  for (double angle : {20.0, 30.0})
    for (double area : {0.0, 0.005}) {
      auto o = options(angle, area);
      o.threads = 1;
      const auto one = gg_refine::refine(d, o);
      SCOPED_TRACE("angle " + std::to_string(angle) + " area " + std::to_string(area));
      gg_refine::expect_quality(d, one, o);
      EXPECT_TRUE(one.small_angles.empty());
      o.threads = 0;
      const auto all = gg_refine::refine(d, o);
      EXPECT_EQ(one.points, all.points);
      EXPECT_EQ(one.triangles, all.triangles);
      EXPECT_EQ(one.neighbors, all.neighbors);
    }
}

// Regions with their own bounds and attributes, a sizing grid and a sizing function.
TEST(Refine2d, RegionsAndSizing) {
  // Two halves of a square, split by a segment.
  gg_refine::Domain d{{"two regions",
                       {0, 0, 1, 0, 1, 1, 0, 1, .5, 0, .5, 1},
                       {0, 4, 4, 1, 1, 2, 2, 5, 5, 3, 3, 0, 4, 5}},
                      {},
                      true};
  auto o = options(25);
  o.regions = {{.25, .5, 1.0, 1e-3}, {.75, .5, 2.0, 0.0}};
  const auto r = gg_refine::refine(d, o);
  gg_refine::expect_quality(d, r, o);
  const std::vector<double> pts(r.points.begin(), r.points.end());
  double left = 0, right = 0;
  for (std::size_t t = 0; t < r.num_triangles; ++t) {
    const double a = gg_refine::mesh_area(pts, r.triangles.data() + 3 * t, 1);
    ASSERT_TRUE(r.attribute[t] == 1.0 || r.attribute[t] == 2.0);
    if (r.attribute[t] == 1.0) EXPECT_LE(a, 1e-3 * (1 + 1e-12));
    (r.attribute[t] == 1.0 ? left : right) += a;
  }
  EXPECT_NEAR(left, 0.5, 1e-12);
  EXPECT_NEAR(right, 0.5, 1e-12);
  // A grid: fine at the top (row 1), coarse at the bottom; and the same from a function.
  auto g = options(25);
  g.area_grid = {{1e-3, 1e-3, 1e-4, 1e-4}, 2, 2, 0, 0, 1, 1};
  const auto rg = gg_refine::refine(d, g);
  auto f = options(25);
  f.max_area_at = [](double, double y) { return 1e-3 - 9e-4 * y; };
  const auto rf = gg_refine::refine(d, f);
  for (const auto* m : {&rg, &rf}) {
    const std::vector<double> p(m->points.begin(), m->points.end());
    for (std::size_t t = 0; t < std::size_t(m->num_triangles); ++t) {
      double cy = 0;
      for (int k = 0; k < 3; ++k) cy += p[2 * std::size_t(m->triangles[3 * t + k]) + 1] / 3;
      EXPECT_LE(gg_refine::mesh_area(p, m->triangles.data() + 3 * t, 1),
                (1e-3 - 9e-4 * cy) * (1 + 1e-9));
    }
  }
  EXPECT_GT(rg.num_triangles, 300u);
}

// The Steiner limit: no more points than allowed, the triangles left bad reported.
TEST(Refine2d, SteinerLimit) {
  const Domain d = gg_refine::square_with_hole();
  auto o = options(30, 1e-4);
  o.max_steiner_points = 40;
  const auto r = gg_refine::refine(d, o);
  EXPECT_LE(r.num_points, d.g.xy.size() / 2 + 40);
  EXPECT_FALSE(r.large_triangles.empty());
  for (auto why : r.small_angle_reasons) EXPECT_EQ(why, std::int8_t(SmallAngle::Limit));
}

TEST(Refine2d, BadInputIsRefused) {
  const Domain d = gg_refine::square_with_hole();
  const std::int64_t n = std::int64_t(d.g.xy.size() / 2), m = std::int64_t(d.g.segs.size() / 2);
  auto expect_error = [&](Refine2dOptions o, ErrorCode code, const char* what) {
    try {
      refine2d(d.g.xy.data(), n, d.g.segs.data(), m, o);
      ADD_FAILURE() << "no error for " << what;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), code) << what << ": " << e.what();
    }
  };
  expect_error(options(40), ErrorCode::InvalidArgument, "an angle above 33.8");
  expect_error(options(-1), ErrorCode::InvalidArgument, "a negative angle");
  expect_error(options(20, -1), ErrorCode::InvalidArgument, "a negative area");
  auto g = options(20);
  g.area_grid = {{1, 2, 3}, 2, 2, 0, 0, 1, 1};
  expect_error(g, ErrorCode::InvalidArgument, "a grid of the wrong size");
  auto s = options(20);
  s.max_steiner_points = -5;
  expect_error(s, ErrorCode::InvalidArgument, "a negative Steiner limit");
  std::vector<std::int32_t> bad = d.g.segs;
  bad[3] = 99;
  Refine2dOptions o = options(20);
  EXPECT_THROW(refine2d(d.g.xy.data(), n, bad.data(), m, o), Error);
  try {
    refine2d_device(d.g.xy.data(), n, bad.data(), m, o);
    ADD_FAILURE() << "the device entry took point 99";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("names point 99"), std::string::npos) << e.what();
  }
  // Crossing segments are named; Split and a host sizing function are host-entry only.
  const std::vector<double> xy{0, 0, 1, 1, 1, 0, 0, 1};
  const std::vector<std::int32_t> cross{0, 1, 2, 3};
  try {
    refine2d(xy.data(), 4, cross.data(), 2, o);
    ADD_FAILURE() << "crossing segments taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("segments 0 and 1"), std::string::npos) << e.what();
  }
  auto split = o;
  split.crossings = Cdt2dOptions::Crossings::Split;
  const auto r = refine2d(xy.data(), 4, cross.data(), 2, split);
  EXPECT_EQ(r.num_input_points, 5);
  EXPECT_THROW(refine2d_device(xy.data(), 4, cross.data(), 2, split), Error);
  auto fn = o;
  fn.max_area_at = [](double, double) { return 1.0; };
  EXPECT_THROW(refine2d_device(xy.data(), 4, cross.data(), 0, fn), Error);
}

// The caller's arrays (Refine2dOptions::into), from both entries: the same values as the
// library's arrays, the library's left empty; a short array is refused before anything is
// written.
TEST(Refine2d, IntoCallersArrays) {
  using gg_test::CallerArray;
  const Domain d = gg_refine::square_with_hole();
  const std::int64_t n = std::int64_t(d.g.xy.size() / 2), m = std::int64_t(d.g.segs.size() / 2);
  auto o = options(30, 2e-3);
  o.regions = {{0.05, 0.05, 4.0, 0.0}};
  const auto ref = refine2d(d.g.xy.data(), n, d.g.segs.data(), m, o);
  const std::int64_t np = ref.num_points, nt = ref.num_triangles,
                     ns = std::int64_t(ref.subsegment_of.size());
  ASSERT_GT(nt, 0);
  ASSERT_EQ(std::int64_t(ref.attribute.size()), nt);
  for (bool device : {false, true}) {
    SCOPED_TRACE(device ? "device entry" : "host entry");
    CallerArray<double> p(2 * np + 5, 7), at(nt, 7);
    CallerArray<std::int32_t> t(3 * nt, 7), nb(3 * nt + 1, 7), sg(3 * nt, 7), dup(np, 7),
        sub(2 * ns, 7), sub_of(ns, 7);
    auto mine = o;
    mine.into = {p.buf(),  at.buf(),  t.buf(),   nb.buf(),
                 sg.buf(), dup.buf(), sub.buf(), sub_of.buf()};
    if (device) {
      const auto r = refine2d_device(d.g.xy.data(), n, d.g.segs.data(), m, mine);
      EXPECT_FALSE(r.points || r.triangles || r.neighbors || r.segment_of || r.duplicate_of ||
                   r.attribute || r.subsegments || r.subsegment_of);
      ASSERT_EQ(r.num_points, np);
      ASSERT_EQ(r.num_triangles, nt);
      ASSERT_EQ(r.num_subsegments, ns);
    } else {
      const auto r = refine2d(d.g.xy.data(), n, d.g.segs.data(), m, mine);
      EXPECT_TRUE(r.points.empty() && r.triangles.empty() && r.neighbors.empty() &&
                  r.segment_of.empty() && r.duplicate_of.empty() && r.attribute.empty() &&
                  r.subsegments.empty() && r.subsegment_of.empty());
      EXPECT_EQ(r.small_angles, ref.small_angles);
      ASSERT_EQ(r.num_points, np);
      ASSERT_EQ(r.num_triangles, nt);
    }
    EXPECT_EQ(gg_test::host_prefix(p.v.data(), 2 * np), ref.points);
    EXPECT_EQ(p.v[std::size_t(2 * np)], 7.0);  // (nothing past the result's length)
    EXPECT_EQ(t.v, ref.triangles);
    EXPECT_EQ(gg_test::host_prefix(nb.v.data(), 3 * nt), ref.neighbors);
    EXPECT_EQ(sg.v, ref.segment_of);
    EXPECT_EQ(dup.v, ref.duplicate_of);
    EXPECT_EQ(at.v, ref.attribute);
    EXPECT_EQ(sub.v, ref.subsegments);
    EXPECT_EQ(sub_of.v, ref.subsegment_of);
    // One array too short: refused, and nothing written.
    CallerArray<double> p2(2 * np, 7);
    CallerArray<std::int32_t> sub2(2 * ns - 1, 7);
    mine.into = {p2.buf(), {}, {}, {}, {}, {}, sub2.buf(), {}};
    gg_test::expect_refused(
        [&] {
          device ? (void)refine2d_device(d.g.xy.data(), n, d.g.segs.data(), m, mine)
                 : (void)refine2d(d.g.xy.data(), n, d.g.segs.data(), m, mine);
        },
        "into.subsegments holds " + std::to_string(2 * ns - 1) +
            " elements; this result needs at least " + std::to_string(2 * ns));
    EXPECT_TRUE(p2.untouched(7) && sub2.untouched(7));
  }
}
