// Inputs and checks shared by the CPU and CUDA 2D Delaunay tests.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/generate.hpp"
#include "../common/kept_operations.hpp"
#include "verify.hpp"

namespace gg_del2d {
using namespace gpugeom;

struct Case {
  std::string name;
  std::vector<Point2> pts;
};

// Exactly degenerate and awkward inputs the generators do not make.
inline std::vector<Case> degenerate_cases() {
  std::vector<Case> cs;
  {  // 12 integer points exactly on the circle of radius 5, plus its centre
    Case c{"integer circle", {}};
    for (int x = -5; x <= 5; ++x)
      for (int y = -5; y <= 5; ++y)
        if (x * x + y * y == 25) c.pts.push_back({double(x), double(y)});
    cs.push_back(c);
    c.name = "integer circle and centre";
    c.pts.push_back({0, 0});
    cs.push_back(c);
  }
  {  // many exactly cocircular points: Pythagorean points on x^2 + y^2 = 5^2 * 13^2 * 17^2
    Case c{"big integer circle", {}};
    const long r2 = 5L * 5 * 13 * 13 * 17 * 17;
    for (long x = -1105; x <= 1105; ++x) {
      long y2 = r2 - x * x;
      long y = std::lround(std::sqrt(double(y2)));
      if (y * y == y2) {
        c.pts.push_back({double(x), double(y)});
        if (y) c.pts.push_back({double(x), double(-y)});
      }
    }
    cs.push_back(c);
  }
  for (int w : {2, 3, 7, 31}) {  // grids: every square cocircular, every row collinear
    Case c{"grid " + std::to_string(w) + "x" + std::to_string(w + 3), {}};
    for (int i = 0; i < w; ++i)
      for (int j = 0; j < w + 3; ++j) c.pts.push_back({double(i), double(j)});
    cs.push_back(c);
  }
  {  // a line of points and one point off it: every triangle shares the apex
    Case c{"fan", {}};
    for (int i = 0; i < 50; ++i) c.pts.push_back({double(i), 0.0});
    c.pts.push_back({20.5, 3.0});
    cs.push_back(c);
  }
  {  // collinear points on every side of a square
    Case c{"square outline", {}};
    for (int i = 0; i < 10; ++i) {
      c.pts.push_back({double(i), 0});
      c.pts.push_back({10, double(i)});
      c.pts.push_back({double(10 - i), 10});
      c.pts.push_back({0, double(10 - i)});
    }
    cs.push_back(c);
  }
  {  // duplicates, some many times, with -0 and +0
    Case c{"duplicates", {}};
    std::mt19937_64 rng(5);
    std::uniform_int_distribution<int> u(0, 20);
    for (int i = 0; i < 400; ++i) c.pts.push_back({double(u(rng)) / 4, double(u(rng)) / 8});
    c.pts.push_back({0.0, 0.0});
    c.pts.push_back({-0.0, 0.0});
    c.pts.push_back({0.0, -0.0});
    cs.push_back(c);
  }
  {  // huge and tiny coordinates together
    Case c{"huge and tiny", {}};
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < 300; ++i) c.pts.push_back({u(rng) * 1e-30, u(rng) * 1e-30});
    for (int i = 0; i < 300; ++i) c.pts.push_back({u(rng) * 1e40, u(rng) * 1e40});
    c.pts.push_back({1e-40, 0});
    cs.push_back(c);
  }
  {  // nearly collinear: a long thin sliver of points
    Case c{"sliver", {}};
    for (int i = 0; i < 500; ++i) c.pts.push_back({double(i), double(i) * 1e-14 * (i % 3)});
    cs.push_back(c);
  }
  return cs;
}

inline std::vector<Case> distribution_cases(const std::vector<std::int64_t>& sizes,
                                            std::uint64_t seed) {
  std::vector<Case> cs;
  for (const auto& d : distributions2d())
    for (std::int64_t n : sizes)
      cs.push_back({d + " " + std::to_string(n), generate2d(d, n, seed)});
  return cs;
}

// Inputs for the digital method (issue 20), each with its grid side (0: chosen from n): every
// distribution on the automatic grid and on a coarse one (many points share a pixel, many sites
// move across their neighbours' edges), the degenerate cases, clusters, a lattice with points a
// hair off it (below the grid's resolution) and exactly cocircular integer points.
struct DigitalCase {
  std::string name;
  std::vector<Point2> pts;
  std::int64_t grid = 0;
};

inline std::vector<DigitalCase> digital_cases(std::int64_t n, std::uint64_t seed) {
  std::vector<DigitalCase> cs;
  for (const auto& d : distributions2d()) {
    cs.push_back({d + " " + std::to_string(n), generate2d(d, n, seed), 0});
    cs.push_back({d + " " + std::to_string(n) + " on 64", generate2d(d, n, seed + 1), 64});
  }
  for (const Case& c : degenerate_cases()) {
    cs.push_back({c.name, c.pts, 0});
    cs.push_back({c.name + " on 8", c.pts, 8});
  }
  std::mt19937_64 r(seed);
  std::uniform_real_distribution<double> U(0, 1);
  std::normal_distribution<double> N(0, 1);
  {
    DigitalCase c{"clusters", {}, 0};
    for (int k = 0; k < 20; ++k) {
      const double cx = U(r), cy = U(r), sd = 0.0005 + 0.01 * U(r);
      for (std::int64_t i = 0; i < n / 20; ++i) c.pts.push_back({cx + sd * N(r), cy + sd * N(r)});
    }
    cs.push_back(c);
  }
  {
    DigitalCase c{"lattice a hair off", {}, 256};
    for (int y = 0; y < 70; ++y)
      for (int x = 0; x < 70; ++x)
        c.pts.push_back({x + 1e-9 * (U(r) - 0.5), y + ((x + y) % 3 ? 0.0 : 1e-12)});
    cs.push_back(c);
  }
  {
    DigitalCase c{"integer lattice with duplicates", {}, 0};
    for (int y = 0; y < 50; ++y)
      for (int x = 0; x < 50; ++x) c.pts.push_back({double(x), double(y)});
    for (int i = 0; i < 300; ++i) c.pts.push_back(c.pts[std::size_t(i * 7)]);
    cs.push_back(c);
  }
  return cs;
}

// The checker's verdict plus what the checker does not look at: neighbours and the duplicate
// map.
inline void expect_valid(const std::vector<Point2>& pts, const Triangulation2d& t) {
  const std::int64_t n = std::int64_t(pts.size());
  ASSERT_EQ(std::int64_t(t.duplicate_of.size()), n);
  std::int64_t ndup = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int32_t d = t.duplicate_of[i];
    if (d < 0) continue;
    ++ndup;
    ASSERT_LT(d, i) << "point " << i;
    ASSERT_EQ(t.duplicate_of[d], -1);
    ASSERT_TRUE(pts[d].x == pts[i].x && pts[d].y == pts[i].y) << "point " << i;
  }
  EXPECT_EQ(ndup, t.num_duplicates);
  const auto r = verify::check_delaunay2d(&pts.data()->x, n, t.triangles.data(), t.num_triangles,
                                          t.duplicate_of.data());
  ASSERT_TRUE(r.ok) << r.message;
  // neighbours: opposite vertex k, shared edge, symmetric
  const std::int64_t nt = t.num_triangles;
  ASSERT_EQ(t.neighbors.size(), t.triangles.size());
  std::int64_t hull = 0;
  for (std::int64_t c = 0; c < nt; ++c)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t o = t.neighbors[3 * c + k];
      const std::int32_t u = t.triangles[3 * c + (k + 1) % 3], v = t.triangles[3 * c + (k + 2) % 3];
      if (o < 0) {
        ++hull;
        continue;
      }
      ASSERT_LT(o, nt);
      int shared = 0, back = 0;
      for (int j = 0; j < 3; ++j) {
        const std::int32_t w = t.triangles[3 * o + j];
        shared += (w == u || w == v);
        back += t.neighbors[3 * o + j] == c;
      }
      ASSERT_EQ(shared, 2) << "triangle " << c << " edge " << k;
      ASSERT_EQ(back, 1) << "triangle " << c << " edge " << k;
    }
  // Euler: triangles = 2 * vertices - 2 - hull edges
  const std::int64_t nv = n - ndup;
  EXPECT_EQ(nt, 2 * nv - 2 - hull);
}

// Triangles as a canonical set (each rotated to start at its smallest index), to compare
// triangulations whose order differs.
inline std::vector<std::array<std::int32_t, 3>> triangle_set(const std::int32_t* tris,
                                                             std::size_t nt) {
  return gpugeom::verify::canonical_triangles(tris, std::int64_t(nt));
}
inline std::vector<std::array<std::int32_t, 3>> triangle_set(const Triangulation2d& t) {
  return triangle_set(t.triangles.data(), std::size_t(t.num_triangles));
}

// A DynamicDelaunay2d fed a case's points in a random order and in chunks of random sizes (the
// first chunk grows until it is not degenerate): after every call, valid by the checker and the
// same triangles, neighbours' validity and duplicate map as a fresh delaunay2d of the points so
// far. Returns the final triangulation (for comparisons across executors).
inline Triangulation2d follow_in_chunks(const Case& c, const Delaunay2dOptions& opt,
                                        std::uint64_t seed) {
  std::vector<Point2> all = c.pts;
  std::mt19937_64 rng(seed);
  std::shuffle(all.begin(), all.end(), rng);
  const std::size_t n = all.size();
  std::size_t k = std::min<std::size_t>(n, 3 + rng() % std::max<std::size_t>(1, n / 4));
  std::unique_ptr<DynamicDelaunay2d> dyn;
  for (;;) {
    try {
      dyn = std::make_unique<DynamicDelaunay2d>(&all.data()->x, std::int64_t(k), opt);
      break;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::DegenerateInput) << e.what();
      if (k == n) ADD_FAILURE() << "no triangulation of all points";
      if (k == n) return {};
      k = std::min(n, 2 * k);
    }
  }
  Delaunay2dOptions fresh_opt;
  fresh_opt.backend = opt.backend;
  std::size_t step = 0;
  for (;;) {
    std::vector<Point2> sofar(all.begin(), all.begin() + std::ptrdiff_t(k));
    SCOPED_TRACE(std::to_string(k) + " of " + std::to_string(n) + " points");
    const Triangulation2d t = dyn->triangulation();
    EXPECT_EQ(dyn->num_points(), std::int64_t(k));
    expect_valid(sofar, t);
    const Triangulation2d fresh = delaunay2d(sofar, fresh_opt);
    EXPECT_EQ(triangle_set(t), triangle_set(fresh));
    // array for array: the output's order depends on the triangles alone, not on the slots
    // the kept triangulation's history left
    EXPECT_EQ(t.triangles, fresh.triangles);
    EXPECT_EQ(t.neighbors, fresh.neighbors);
    EXPECT_EQ(t.duplicate_of, fresh.duplicate_of);
    if (k == n || ::testing::Test::HasFailure()) return t;
    const std::size_t left = n - k;
    // one point, then two, then a quarter to a half of what is left
    const std::size_t add = step < 2 ? step + 1 : left / 4 + 1 + rng() % (left / 4 + 1);
    ++step;
    dyn->insert(&all[k].x, std::int64_t(std::min(add, left)));
    k += std::min(add, left);
  }
}

// DynamicDelaunay2d for gg_test::KeptOperations.
struct Kept2d : gg_test::KeptTriangulation<Kept2d> {
  using Point = Point2;
  using Dyn = DynamicDelaunay2d;
  using Result = Triangulation2d;
  using Options = Delaunay2dOptions;
  static constexpr int kVerts = 3, kDim = 2;
  static Result fresh(const std::vector<Point2>& p, const Options& o) {
    Options f;
    f.backend = o.backend;
    return delaunay2d(p, f);
  }
  static Result current(const Dyn& d) { return d.triangulation(); }
  static void valid(const std::vector<Point2>& p, const Result& t) { expect_valid(p, t); }
  static const std::int32_t* simplices(const Result& t) { return t.triangles.data(); }
  static const std::int32_t* neighbors(const Result& t) { return t.neighbors.data(); }
  static std::int64_t count(const Result& t) { return t.num_triangles; }
  static std::vector<std::int32_t> dup(const Result& t) {
    return std::vector<std::int32_t>(t.duplicate_of.begin(), t.duplicate_of.end());
  }
  static void shift(Point2& p, double s, std::mt19937_64& rng) {
    std::normal_distribution<double> N(0, s);
    p.x += N(rng), p.y += N(rng);
  }
};

}  // namespace gg_del2d
