// Delaunay refinement on the CPU executor: Triangle's classic domains, small input angles,
// random PSLGs, regions and sizing, the Steiner limit, thread counts and bad options; every mesh
// judged by the exact checker with the bounds.
#include <gtest/gtest.h>

#include <cstdio>

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
        if (area > 0 || angle > 30) EXPECT_GT(r.stats.counters.at("steiner_points"), 0);
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
