// Domains for the refinement tests (Triangle's classic inputs, written here): a square with a
// square hole, the letter A, a domain with 5-degree input angles, a coastline, random PSLGs; and
// the checks every refined mesh must pass.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "../cdt2d/cdt2d_cases.hpp"
#include "gpugeom/refine2d.hpp"
#include "verify.hpp"

namespace gg_refine {

using gg_cdt::Pslg;

struct Domain {
  Pslg g;
  std::vector<gpugeom::Point2> holes;
  bool enclosed = true;
};

// A closed polygon's vertices appended to g, its edges as segments.
inline void polygon(Pslg& g, const std::vector<double>& xy) {
  const std::int32_t first = std::int32_t(g.xy.size() / 2), m = std::int32_t(xy.size() / 2);
  g.xy.insert(g.xy.end(), xy.begin(), xy.end());
  for (std::int32_t i = 0; i < m; ++i)
    g.segs.insert(g.segs.end(), {first + i, first + (i + 1) % m});
}

inline Domain square_with_hole() {
  Domain d{{"square with a hole", {}, {}}, {{0.5, 0.5}}, true};
  polygon(d.g, {0, 0, 1, 0, 1, 1, 0, 1});
  polygon(d.g, {0.3, 0.3, 0.7, 0.3, 0.7, 0.7, 0.3, 0.7});
  return d;
}

// An A: the outline (legs, feet, apex) and the triangular hole under the apex.
inline Domain letter_a() {
  Domain d{{"letter A", {}, {}}, {{0.5, 0.62}}, true};
  polygon(d.g, {0.0, 0.0, 0.2, 0.0, 0.3, 0.3, 0.7, 0.3, 0.8, 0.0, 1.0, 0.0, 0.6, 1.0, 0.4, 1.0});
  polygon(d.g, {0.37, 0.45, 0.63, 0.45, 0.5, 0.8});
  return d;
}

// A fan of spokes from the origin 5 degrees apart, closed by an outer arc of chords: many
// 5-degree input angles meeting at one vertex.
inline Domain small_angles() {
  Domain d{{"5-degree input angles", {}, {}}, {}, true};
  d.g.xy = {0, 0};
  const double pi = 3.141592653589793;
  const int spokes = 7;
  for (int i = 0; i < spokes; ++i) {
    const double a = i * 5.0 * pi / 180;
    d.g.xy.insert(d.g.xy.end(), {std::cos(a), std::sin(a)});
    d.g.segs.insert(d.g.segs.end(), {0, i + 1});
    if (i + 1 < spokes) d.g.segs.insert(d.g.segs.end(), {i + 1, i + 2});
  }
  return d;
}

inline Domain coastline(std::int64_t m) {
  Domain d{gg_cdt::coastline_pslg(m, 7), {}, true};
  d.g.xy.resize(2 * std::size_t(m));  // (the outline only: its scattered points lie outside)
  return d;
}

inline Domain random_domain(std::int64_t n, unsigned seed) {
  return Domain{gg_cdt::random_pslg(n, n / 2, seed), {}, false};
}

inline gpugeom::RefinedMesh2d refine(const Domain& d, gpugeom::Refine2dOptions o) {
  o.domain = d.enclosed ? gpugeom::Cdt2dOptions::Domain::Enclosed
                        : gpugeom::Cdt2dOptions::Domain::ConvexHull;
  o.holes = d.holes;
  return gpugeom::refine2d(d.g.xy.data(), std::int64_t(d.g.xy.size() / 2), d.g.segs.data(),
                           std::int64_t(d.g.segs.size() / 2), o);
}

inline double mesh_area(const std::vector<double>& xy, const std::int32_t* t, std::size_t nt) {
  double a = 0;
  for (std::size_t c = 0; c < nt; ++c) {
    const double* p = &xy[2 * std::size_t(t[3 * c])];
    const double* q = &xy[2 * std::size_t(t[3 * c + 1])];
    const double* s = &xy[2 * std::size_t(t[3 * c + 2])];
    a += ((q[0] - p[0]) * (s[1] - p[1]) - (q[1] - p[1]) * (s[0] - p[0])) / 2;
  }
  return a;
}

// The exact checker with the bounds, the input points kept in place, the reasons known, and the
// mesh covering the same area as the unrefined constrained triangulation of the domain.
inline void expect_quality(const Domain& d, const gpugeom::RefinedMesh2d& r,
                           const gpugeom::Refine2dOptions& o) {
  const std::vector<double> pts(r.points.begin(), r.points.end());
  ASSERT_GE(r.num_points, d.g.xy.size() / 2) << d.g.name;
  for (std::size_t i = 0; i < d.g.xy.size(); ++i) ASSERT_EQ(pts[i], d.g.xy[i]) << d.g.name;
  ASSERT_EQ(r.small_angles.size(), r.small_angle_reasons.size());
  for (auto why : r.small_angle_reasons)
    EXPECT_TRUE(why >= 1 && why <= 3) << d.g.name << ": reason " << int(why);
  const auto rep = gpugeom::verify::check_refined_mesh2d(
      pts.data(), r.num_points, r.triangles.data(), r.num_triangles, r.segment_of.data(),
      d.g.segs.data(), std::int64_t(d.g.segs.size() / 2), r.duplicate_of.data(), o.min_angle,
      o.max_area, r.small_angles.data(), std::int64_t(r.small_angles.size()));
  ASSERT_TRUE(rep.ok) << d.g.name << ": " << rep.message;
  gpugeom::Cdt2dOptions c;
  c.backend = gpugeom::Backend::Cpu;
  c.domain = d.enclosed ? gpugeom::Cdt2dOptions::Domain::Enclosed
                        : gpugeom::Cdt2dOptions::Domain::ConvexHull;
  c.holes = d.holes;
  const auto base = gpugeom::cdt2d(d.g.xy.data(), std::int64_t(d.g.xy.size() / 2), d.g.segs.data(),
                                   std::int64_t(d.g.segs.size() / 2), c);
  const double a0 = mesh_area(d.g.xy, base.triangles.data(), base.num_triangles);
  const double a1 = mesh_area(pts, r.triangles.data(), r.num_triangles);
  EXPECT_NEAR(a1, a0, 1e-9 * std::fabs(a0)) << d.g.name;
}

}  // namespace gg_refine
