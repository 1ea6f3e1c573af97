// Shared by the CPU and CUDA 3D Delaunay tests: the full validation of a result (the inputs are
// the hull tests' distributions and degenerate sets, tests/hull3d/hull3d_cases.hpp).
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <algorithm>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "../common/kept_operations.hpp"
#include "../hull3d/hull3d_cases.hpp"
#include "gpugeom/delaunay3d.hpp"
#include "verify.hpp"

namespace gg_del3d {
using gg_hull3d::Case;
using gpugeom::Point3;

// The exact checker, plus what it does not see: neighbours (symmetric, across the face opposite
// each vertex, -1 exactly on the hull), the hull facets, the vertex map and the duplicate map.
inline void expect_valid(const std::vector<Point3>& pts, const gpugeom::Triangulation3d& t) {
  const double* p = &pts.data()->x;
  const std::int64_t n = std::int64_t(pts.size());
  const auto nt = t.num_tetrahedra;
  auto r = gpugeom::verify::check_delaunay3d(p, n, t.tetrahedra.data(), nt, t.duplicate_of.data());
  ASSERT_TRUE(r.ok) << r.message;
  ASSERT_EQ(t.neighbors.size(), t.tetrahedra.size());
  std::int64_t hull = 0;
  for (std::int64_t c = 0; c < nt; ++c)
    for (int k = 0; k < 4; ++k) {
      const std::int32_t o = t.neighbors[4 * c + k];
      if (o < 0) {
        ++hull;
        continue;
      }
      ASSERT_LT(o, nt);
      std::set<std::int32_t> f;
      for (int j = 0; j < 4; ++j)
        if (j != k) f.insert(t.tetrahedra[4 * c + j]);
      int back = -1, shared = 0;
      for (int j = 0; j < 4; ++j) {
        if (t.neighbors[4 * o + j] == c) back = j;
        shared += f.count(t.tetrahedra[4 * o + j]) ? 1 : 0;
      }
      ASSERT_GE(back, 0) << "tetrahedron " << c << " neighbour " << k << " does not point back";
      ASSERT_EQ(shared, 3) << "tetrahedron " << c << " neighbour " << k << " shares no face";
      ASSERT_EQ(f.count(t.tetrahedra[4 * o + back]), 0u);
    }
  ASSERT_EQ(std::int64_t(t.hull_facets.size()), 3 * hull);
  ASSERT_EQ(t.vertex_to_simplex.size(), pts.size());
  // The vertex map's rule, which both executors keep: each vertex's last tetrahedron.
  std::vector<std::int32_t> last(pts.size(), -1);
  for (std::int64_t e = 0; e < 4 * nt; ++e)
    last[std::size_t(t.tetrahedra[std::size_t(e)])] = std::int32_t(e / 4);
  std::int64_t dups = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int32_t s = t.vertex_to_simplex[std::size_t(i)];
    const std::int32_t d = t.duplicate_of[std::size_t(i)];
    const std::int32_t v = d >= 0 ? d : std::int32_t(i);
    if (d >= 0) {
      ++dups;
      ASSERT_LT(d, i);
      ASSERT_EQ(pts[std::size_t(d)].x, pts[std::size_t(i)].x);
      ASSERT_EQ(pts[std::size_t(d)].y, pts[std::size_t(i)].y);
      ASSERT_EQ(pts[std::size_t(d)].z, pts[std::size_t(i)].z);
    }
    ASSERT_TRUE(s >= 0 && s < nt) << "point " << i;
    bool has = false;
    for (int k = 0; k < 4; ++k) has = has || t.tetrahedra[4 * std::size_t(s) + k] == v;
    ASSERT_TRUE(has) << "vertex_to_simplex of point " << i;
    ASSERT_EQ(s, last[std::size_t(v)]) << "vertex_to_simplex of point " << i << " is not its last";
  }
  ASSERT_EQ(dups, t.num_duplicates);
}

// Tetrahedra as a canonical set (sorted vertices), to compare executors and runs.
template <class V>
inline std::set<std::array<std::int32_t, 4>> tet_set(const V& t) {
  std::set<std::array<std::int32_t, 4>> s;
  for (std::size_t c = 0; c < t.size() / 4; ++c) {
    std::array<std::int32_t, 4> a{t[4 * c], t[4 * c + 1], t[4 * c + 2], t[4 * c + 3]};
    std::sort(a.begin(), a.end());
    s.insert(a);
  }
  return s;
}

// The same arrays, entry for entry: tetrahedra in the same order with the same vertex order,
// neighbours, the vertex map, the hull facets and the duplicate map (determinism is about the
// bytes, not only the set of tetrahedra).
inline void expect_same_arrays(const gpugeom::Triangulation3d& a, const gpugeom::Triangulation3d& b,
                               const std::string& what) {
  auto same = [&](const auto& x, const auto& y, const char* name) {
    ASSERT_EQ(x.size(), y.size()) << what << ": " << name;
    for (std::size_t i = 0; i < x.size(); ++i)
      ASSERT_EQ(x[i], y[i]) << what << ": " << name << " differ first at " << i;
  };
  same(a.tetrahedra, b.tetrahedra, "tetrahedra");
  same(a.neighbors, b.neighbors, "neighbors");
  same(a.vertex_to_simplex, b.vertex_to_simplex, "vertex_to_simplex");
  same(a.hull_facets, b.hull_facets, "hull_facets");
  same(a.duplicate_of, b.duplicate_of, "duplicate_of");
}

// A DynamicDelaunay3d fed a case's points in a random order and in chunks of random sizes (the
// first chunk grows until it is not degenerate): after every call, valid by the checker and the
// same tetrahedra, hull facets and duplicate map as a fresh delaunay3d of the points so far.
// Returns the final result (for comparisons across executors).
inline gpugeom::Triangulation3d follow_in_chunks(const Case& c,
                                                 const gpugeom::Delaunay3dOptions& opt,
                                                 std::uint64_t seed) {
  using namespace gpugeom;
  std::vector<Point3> all = c.pts;
  std::mt19937_64 rng(seed);
  std::shuffle(all.begin(), all.end(), rng);
  const std::size_t n = all.size();
  std::size_t k = std::min<std::size_t>(n, 4 + rng() % std::max<std::size_t>(1, n / 4));
  std::unique_ptr<DynamicDelaunay3d> dyn;
  for (;;) {
    try {
      dyn = std::make_unique<DynamicDelaunay3d>(&all.data()->x, std::int64_t(k), opt);
      break;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::DegenerateInput) << e.what();
      if (k == n) ADD_FAILURE() << "no tetrahedralisation of all points";
      if (k == n) return {};
      k = std::min(n, 2 * k);
    }
  }
  Delaunay3dOptions fresh_opt;
  fresh_opt.backend = opt.backend;
  std::size_t step = 0;
  for (;;) {
    std::vector<Point3> sofar(all.begin(), all.begin() + std::ptrdiff_t(k));
    SCOPED_TRACE(std::to_string(k) + " of " + std::to_string(n) + " points");
    const Triangulation3d t = dyn->tetrahedralisation();
    EXPECT_EQ(dyn->num_points(), std::int64_t(k));
    EXPECT_EQ(dyn->num_tetrahedra(), t.num_tetrahedra);
    expect_valid(sofar, t);
    const Triangulation3d fresh = delaunay3d(sofar, fresh_opt);
    EXPECT_EQ(tet_set(t.tetrahedra), tet_set(fresh.tetrahedra));
    EXPECT_EQ(t.num_hull_facets, fresh.num_hull_facets);
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

// DynamicDelaunay3d for gg_test::KeptOperations.
struct Kept3d : gg_test::KeptTriangulation<Kept3d> {
  using Point = gpugeom::Point3;
  using Dyn = gpugeom::DynamicDelaunay3d;
  using Result = gpugeom::Triangulation3d;
  using Options = gpugeom::Delaunay3dOptions;
  static constexpr int kVerts = 4, kDim = 3;
  static Result fresh(const std::vector<Point>& p, const Options& o) {
    Options f;
    f.backend = o.backend;
    return gpugeom::delaunay3d(p, f);
  }
  static Result current(const Dyn& d) { return d.tetrahedralisation(); }
  static void valid(const std::vector<Point>& p, const Result& t) { expect_valid(p, t); }
  static const std::int32_t* simplices(const Result& t) { return t.tetrahedra.data(); }
  static const std::int32_t* neighbors(const Result& t) { return t.neighbors.data(); }
  static std::int64_t count(const Result& t) { return t.num_tetrahedra; }
  static std::vector<std::int32_t> dup(const Result& t) {
    return std::vector<std::int32_t>(t.duplicate_of.begin(), t.duplicate_of.end());
  }
  static void shift(Point& p, double s, std::mt19937_64& rng) {
    std::normal_distribution<double> N(0, s);
    p.x += N(rng), p.y += N(rng), p.z += N(rng);
  }
};

}  // namespace gg_del3d
