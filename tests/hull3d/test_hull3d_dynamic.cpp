// DynamicHull3d (issue 47) on the CPU executor: random inserts, moves and removals give a fresh
// hull of the points left; an insertion looks at the old vertices and the new points only; a
// removal that takes no vertex keeps the hull; refusals change nothing.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "hull3d_cases.hpp"

using namespace gpugeom;
using gg_hull3d::cpu;
using gg_hull3d::expect_valid;
using gg_hull3d::facet_set;

namespace {

// The hull's arrays, all of them (a refused call must leave every one as it was).
struct Snapshot {
  std::vector<std::int32_t> t, nb, v;
  std::vector<double> eq;
  std::int64_t n = 0, removed = 0;
  explicit Snapshot(const DynamicHull3d& d) {
    const auto h = d.hull();
    t.assign(h.triangles.begin(), h.triangles.end());
    nb.assign(h.neighbors.begin(), h.neighbors.end());
    v.assign(h.vertices.begin(), h.vertices.end());
    eq.assign(h.equations.begin(), h.equations.end());
    n = d.num_points(), removed = d.num_removed();
  }
  bool operator==(const Snapshot& o) const {
    return t == o.t && nb == o.nb && v == o.v && eq == o.eq && n == o.n && removed == o.removed;
  }
};

// The hull of the points not removed, in the dynamic object's indices: equal facets and vertices.
void expect_fresh(const DynamicHull3d& d, const std::vector<Point3>& p,
                  const std::vector<char>& gone) {
  std::vector<Point3> live;
  std::vector<std::int32_t> ids;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!gone[i]) live.push_back(p[i]), ids.push_back(std::int32_t(i));
  const auto f = convex_hull3d(live, cpu());
  std::vector<std::int32_t> t, v;
  for (auto x : f.triangles) t.push_back(ids[std::size_t(x)]);
  for (auto x : f.vertices) v.push_back(ids[std::size_t(x)]);
  const auto h = d.hull();
  EXPECT_EQ(facet_set(std::vector<std::int32_t>(h.triangles.begin(), h.triangles.end())),
            facet_set(t));
  EXPECT_EQ(std::vector<std::int32_t>(h.vertices.begin(), h.vertices.end()), v);
}

template <class F>
ErrorCode refused(const DynamicHull3d& d, F call) {
  const Snapshot before(d);
  try {
    call();
  } catch (const Error& e) {
    EXPECT_FALSE(std::string(e.what()).empty());
    EXPECT_TRUE(Snapshot(d) == before) << "a refused call changed the hull";
    return e.code();
  }
  return ErrorCode::Cuda;  // "no error": no test expects this code
}

}  // namespace

// insert, move and remove in random sequences: after every call the facets and extreme points of
// a fresh hull of the points left, on every distribution and degenerate case.
TEST(DynamicHull3d, RandomOperationsGiveTheFreshHull) {
  auto cases = gg_hull3d::degenerate_cases();
  for (const auto& c : gg_hull3d::distribution_cases({60, 3000}, 47)) cases.push_back(c);
  gg_test::random_operations<gg_hull3d::KeptHull>(cases, cpu(), 900, 2, 10);
}

TEST(DynamicHull3d, ChangesNeedTracking) {
  gg_test::changes_need_tracking<gg_hull3d::KeptHull>(generate3d("ball", 3000, 45), cpu());
}

// An insertion makes the hull of the old vertices and the new points not strictly inside the old
// hull only: the points inside are never looked at again.
TEST(DynamicHull3d, InsertionLooksAtTheVerticesAndTheNewPointsOnly) {
  auto p = generate3d("ball", 20000, 8);
  DynamicHull3d d(&p.data()->x, std::int64_t(p.size()), cpu());
  EXPECT_EQ(d.stats().hull_candidates, 20000);
  const std::int64_t nv = d.num_vertices();
  auto more = generate3d("ball", 300, 9);
  auto scale = [](std::vector<Point3>& v, double f) {  // about the ball's centre (0.5, 0.5, 0.5)
    for (auto& q : v) q = {0.5 + f * (q.x - 0.5), 0.5 + f * (q.y - 0.5), 0.5 + f * (q.z - 0.5)};
  };
  scale(more, 1.05);  // some outside
  d.insert(&more.data()->x, std::int64_t(more.size()));
  const std::int64_t out = d.stats().outside_points;
  EXPECT_GT(out, 0);
  EXPECT_LT(out, 300);  // (those strictly inside the old hull are not looked at)
  EXPECT_EQ(d.stats().hull_candidates, nv + out);
  p.insert(p.end(), more.begin(), more.end());
  EXPECT_EQ(d.num_points(), std::int64_t(p.size()));
  expect_valid(p, d.hull());
  expect_fresh(d, p, std::vector<char>(p.size(), 0));
  // points strictly inside: the hull's arrays stay as they were
  const Snapshot s(d);
  auto inner = generate3d("ball", 500, 10);
  scale(inner, 0.5);
  d.insert(&inner.data()->x, std::int64_t(inner.size()));
  EXPECT_EQ(d.stats().outside_points, 0);
  Snapshot after(d);
  after.n = s.n;
  EXPECT_TRUE(after == s);
  p.insert(p.end(), inner.begin(), inner.end());
  expect_fresh(d, p, std::vector<char>(p.size(), 0));
}

// Copies: the first given is the vertex; removed, the next copy takes its place. A removal of
// points that are not vertices keeps the hull's arrays as they were.
TEST(DynamicHull3d, RemovalsAndCopies) {
  auto p = generate3d("ball", 2000, 12);
  const auto h0 = convex_hull3d(p, cpu());
  const std::int32_t v = h0.vertices[3];
  p.push_back(p[std::size_t(v)]);  // 2000: a copy of a vertex
  std::vector<char> gone(p.size(), 0);
  DynamicHull3d d(&p.data()->x, std::int64_t(p.size()), cpu());
  const auto h1 = d.hull();
  EXPECT_TRUE(std::binary_search(h1.vertices.begin(), h1.vertices.end(), v));
  expect_fresh(d, p, gone);
  // a point inside: nothing changes
  std::int32_t inside = 0;
  while (std::binary_search(h0.vertices.begin(), h0.vertices.end(), inside)) ++inside;
  const Snapshot s(d);
  d.remove(&inside, 1);
  gone[std::size_t(inside)] = 1;
  EXPECT_EQ(d.stats().removed_vertices, 0);
  Snapshot after(d);
  after.removed = s.removed;
  EXPECT_TRUE(after == s);
  // the vertex: its copy takes its place
  d.remove(&v, 1);
  gone[std::size_t(v)] = 1;
  EXPECT_EQ(d.stats().removed_vertices, 1);
  const auto h = d.hull();
  EXPECT_TRUE(std::binary_search(h.vertices.begin(), h.vertices.end(), 2000));
  EXPECT_FALSE(std::binary_search(h.vertices.begin(), h.vertices.end(), v));
  expect_fresh(d, p, gone);
  // a new copy of a vertex is not one
  const std::int32_t w = h.vertices[0];
  p.push_back(p[std::size_t(w)]);
  gone.push_back(0);
  d.insert(&p.back().x, 1);
  const auto h2 = d.hull();
  EXPECT_FALSE(
      std::binary_search(h2.vertices.begin(), h2.vertices.end(), std::int32_t(p.size() - 1)));
  expect_fresh(d, p, gone);
}

// Bad calls are refused with a typed error and leave every array as it was.
TEST(DynamicHull3d, RefusalsChangeNothing) {
  auto p = generate3d("uniform", 500, 14);
  DynamicHull3d d(&p.data()->x, std::int64_t(p.size()), cpu());
  const std::int32_t out_of_range[] = {3, 500}, twice[] = {7, 7};
  EXPECT_EQ(refused(d, [&] { d.remove(out_of_range, 2); }), ErrorCode::InvalidArgument);
  EXPECT_EQ(refused(d, [&] { d.remove(twice, 2); }), ErrorCode::InvalidArgument);
  const std::int32_t first = 9;
  d.remove(&first, 1);
  EXPECT_EQ(refused(d, [&] { d.remove(&first, 1); }), ErrorCode::InvalidArgument);
  // all but three left
  std::vector<std::int32_t> most;
  for (std::int32_t i = 0; i < 500; ++i)
    if (i != first && i > 2) most.push_back(i);
  EXPECT_EQ(refused(d, [&] { d.remove(most.data(), std::int64_t(most.size())); }),
            ErrorCode::DegenerateInput);
  EXPECT_EQ(refused(d, [&] { d.move(&p.data()->x, 499); }), ErrorCode::InvalidArgument);
  auto flat = p;
  for (auto& q : flat) q.z = 1.5;
  EXPECT_EQ(refused(d, [&] { d.move(&flat.data()->x, 500); }), ErrorCode::DegenerateInput);
  const Point3 bad[2] = {{0.5, 0.5, 0.5}, {std::nan(""), 0, 0}};
  EXPECT_EQ(refused(d, [&] { d.insert(&bad[0].x, 2); }), ErrorCode::InvalidInput);
  Hull3dOptions into = cpu();
  std::vector<std::int32_t> mine(3000);
  into.into.triangles = {mine.data(), std::int64_t(mine.size())};
  try {
    DynamicHull3d e(&p.data()->x, 500, into);
    ADD_FAILURE() << "opt.into accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::Unsupported);
  }
}

// The executor-memory entries on the CPU executor (its memory is the host's) give the host
// entries' results.
TEST(DynamicHull3d, ExecutorMemoryEntries) {
  auto p = generate3d("sphere", 3000, 15);
  DynamicHull3d a(&p.data()->x, 2000, cpu());
  auto b = DynamicHull3d::from_device(&p.data()->x, 2000, cpu());
  a.insert(&p[2000].x, 1000);
  b.insert_device(&p[2000].x, 1000);
  const std::int32_t r[] = {5, 1500, 2500};
  a.remove(r, 3);
  b.remove_device(r, 3);
  auto q = p;
  for (auto& x : q) x.x *= 1.5;
  a.move(&q.data()->x, 3000);
  b.move_device(&q.data()->x, 3000);
  EXPECT_TRUE(Snapshot(a) == Snapshot(b));
  const auto h = a.hull();
  const auto dh = b.device_hull();
  ASSERT_EQ(dh.backend, Backend::Cpu);
  ASSERT_EQ(dh.num_facets, h.num_facets);
  ASSERT_EQ(dh.num_vertices, h.num_vertices);
  EXPECT_EQ(dh.num_points, 3000);
  EXPECT_TRUE(std::equal(h.triangles.begin(), h.triangles.end(), dh.triangles.get()));
  EXPECT_TRUE(std::equal(h.neighbors.begin(), h.neighbors.end(), dh.neighbors.get()));
  EXPECT_TRUE(std::equal(h.vertices.begin(), h.vertices.end(), dh.vertices.get()));
  EXPECT_TRUE(std::equal(h.equations.begin(), h.equations.end(), dh.equations.get()));
}
