// The checkers accept correct structures (built here by brute force from the definitions) and
// reject broken ones: a flipped edge, a missing simplex, a reversed simplex, a reflex hull edge,
// a missing hull face, a point outside, a non-extreme vertex, a wrong distance.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "gpugeom/generate.hpp"
#include "predicates/predicates.hpp"
#include "verify.hpp"

using namespace gpugeom;

namespace {
std::vector<double> S(pred::kInsphereScratch);

std::vector<double> random_points(int dim, int n, unsigned seed) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<double> p(std::size_t(n) * dim);
  for (auto& v : p) v = U(g);
  return p;
}

// Delaunay by definition: every triangle with an empty circumcircle (general position).
std::vector<std::int32_t> brute_delaunay2d(const std::vector<double>& p) {
  const int n = int(p.size() / 2);
  std::vector<std::int32_t> t;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c) {
        int o = pred::orient2d(&p[2 * a], &p[2 * b], &p[2 * c], S.data());
        int x = a, y = o > 0 ? b : c, z = o > 0 ? c : b;
        bool empty = true;
        for (int d = 0; d < n && empty; ++d)
          if (d != a && d != b && d != c)
            empty = pred::incircle(&p[2 * x], &p[2 * y], &p[2 * z], &p[2 * d], S.data()) < 0;
        if (empty) t.insert(t.end(), {x, y, z});
      }
  return t;
}
std::vector<std::int32_t> brute_delaunay3d(const std::vector<double>& p) {
  const int n = int(p.size() / 3);
  std::vector<std::int32_t> t;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c)
        for (int d = c + 1; d < n; ++d) {
          int o = pred::orient3d(&p[3 * a], &p[3 * b], &p[3 * c], &p[3 * d], S.data());
          int v[4] = {a, b, o > 0 ? c : d, o > 0 ? d : c};
          bool empty = true;
          for (int e = 0; e < n && empty; ++e)
            if (e != a && e != b && e != c && e != d)
              empty = pred::insphere(&p[3 * v[0]], &p[3 * v[1]], &p[3 * v[2]], &p[3 * v[3]],
                                     &p[3 * e], S.data()) < 0;
          if (empty) t.insert(t.end(), v, v + 4);
        }
  return t;
}
std::vector<std::int32_t> brute_hull(const std::vector<double>& p) {
  const int n = int(p.size() / 3);
  std::vector<std::int32_t> t;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < n; ++c) {
        if (!(a < b && a < c && b != c)) continue;
        bool face = true;
        for (int d = 0; d < n && face; ++d)
          if (d != a && d != b && d != c)
            face = pred::orient3d(&p[3 * a], &p[3 * b], &p[3 * c], &p[3 * d], S.data()) < 0;
        if (face) t.insert(t.end(), {a, b, c});
      }
  return t;
}

}  // namespace

TEST(Verify, Delaunay2dAcceptsAndRejects) {
  auto p = random_points(2, 40, 1);
  auto t = brute_delaunay2d(p);
  const std::int64_t n = 40, nt = std::int64_t(t.size() / 3);
  auto r = verify::check_delaunay2d(p.data(), n, t.data(), nt);
  ASSERT_TRUE(r.ok) << r.message;
  // Flip one interior edge: still a triangulation, no longer Delaunay.
  bool flipped = false;
  for (std::int64_t i = 0; i < nt && !flipped; ++i)
    for (std::int64_t j = i + 1; j < nt && !flipped; ++j)
      for (int e = 0; e < 3 && !flipped; ++e) {
        int u = t[3 * i + e], v = t[3 * i + (e + 1) % 3], a = t[3 * i + (e + 2) % 3];
        for (int f = 0; f < 3; ++f)
          if (t[3 * j + f] == v && t[3 * j + (f + 1) % 3] == u) {
            int b = t[3 * j + (f + 2) % 3];
            // flip only when the quadrilateral is convex, so the result is a triangulation
            if (pred::orient2d(&p[2 * a], &p[2 * u], &p[2 * b], S.data()) > 0 &&
                pred::orient2d(&p[2 * b], &p[2 * v], &p[2 * a], S.data()) > 0) {
              auto q = t;
              q[3 * i] = a, q[3 * i + 1] = u, q[3 * i + 2] = b;
              q[3 * j] = b, q[3 * j + 1] = v, q[3 * j + 2] = a;
              EXPECT_TRUE(verify::check_triangulation2d(p.data(), n, q.data(), nt).ok);
              auto bad = verify::check_delaunay2d(p.data(), n, q.data(), nt);
              EXPECT_FALSE(bad.ok);
              EXPECT_NE(bad.message.find("not locally Delaunay"), std::string::npos) << bad.message;
              flipped = true;
            }
            break;
          }
      }
  ASSERT_TRUE(flipped);
  {  // a missing triangle
    auto q = t;
    q.erase(q.begin() + 3 * (nt / 2), q.begin() + 3 * (nt / 2) + 3);
    EXPECT_FALSE(verify::check_triangulation2d(p.data(), n, q.data(), nt - 1).ok);
  }
  {  // a reversed triangle
    auto q = t;
    std::swap(q[1], q[2]);
    auto bad = verify::check_triangulation2d(p.data(), n, q.data(), nt);
    EXPECT_FALSE(bad.ok);
    EXPECT_NE(bad.message.find("clockwise"), std::string::npos) << bad.message;
  }
  {  // a duplicated triangle
    auto q = t;
    q.insert(q.end(), t.begin(), t.begin() + 3);
    EXPECT_FALSE(verify::check_triangulation2d(p.data(), n, q.data(), nt + 1).ok);
  }
  {  // an input point that is not a vertex
    auto p2 = p;
    p2.insert(p2.end(), {0.5, 0.5});
    auto bad = verify::check_triangulation2d(p2.data(), n + 1, t.data(), nt);
    EXPECT_FALSE(bad.ok);
    EXPECT_NE(bad.message.find("not a vertex"), std::string::npos) << bad.message;
    std::vector<std::int32_t> dup(n + 1, -1);
    p2[2 * n] = p[0], p2[2 * n + 1] = p[1];  // now an exact duplicate of point 0, reported
    dup[n] = 0;
    EXPECT_TRUE(verify::check_triangulation2d(p2.data(), n + 1, t.data(), nt, dup.data()).ok);
  }
  {  // two copies of the whole triangulation: every edge twice
    auto q = t;
    q.insert(q.end(), t.begin(), t.end());
    EXPECT_FALSE(verify::check_triangulation2d(p.data(), n, q.data(), 2 * nt).ok);
  }
}

// The constrained checker: an interior edge flipped away from Delaunay is accepted exactly when
// it is a segment; a segment crossed by an edge, a segment through a vertex, and segments that
// name no edge are judged as such.
TEST(Verify, ConstrainedDelaunay2dAcceptsAndRejects) {
  auto p = random_points(2, 40, 7);
  auto t = brute_delaunay2d(p);
  const std::int64_t n = 40, nt = std::int64_t(t.size() / 3);
  // No segments, and every Delaunay edge as a segment: the Delaunay triangulation is the CDT.
  EXPECT_TRUE(verify::check_constrained_delaunay2d(p.data(), n, t.data(), nt, nullptr, 0).ok);
  std::vector<std::int32_t> all;
  for (std::int64_t c = 0; c < nt; ++c)
    for (int j = 0; j < 3; ++j) all.insert(all.end(), {t[3 * c + j], t[3 * c + (j + 1) % 3]});
  auto every = verify::check_constrained_delaunay2d(p.data(), n, t.data(), nt, all.data(),
                                                    std::int64_t(all.size() / 2));
  EXPECT_TRUE(every.ok) << every.message;
  int flips = 0;
  for (std::int64_t i = 0; i < nt && flips < 3; ++i)
    for (std::int64_t j = i + 1; j < nt && flips < 3; ++j)
      for (int e = 0; e < 3; ++e) {
        const int u = t[3 * i + e], v = t[3 * i + (e + 1) % 3], a = t[3 * i + (e + 2) % 3];
        int f = 0;
        while (f < 3 && !(t[3 * j + f] == v && t[3 * j + (f + 1) % 3] == u)) ++f;
        if (f == 3) continue;
        const int b = t[3 * j + (f + 2) % 3];
        if (pred::orient2d(&p[2 * a], &p[2 * u], &p[2 * b], S.data()) <= 0 ||
            pred::orient2d(&p[2 * b], &p[2 * v], &p[2 * a], S.data()) <= 0)
          continue;  // flip only convex quadrilaterals: the result is a triangulation
        auto q = t;
        q[3 * i] = a, q[3 * i + 1] = u, q[3 * i + 2] = b;
        q[3 * j] = b, q[3 * j + 1] = v, q[3 * j + 2] = a;
        const std::int32_t ab[2] = {a, b}, uv[2] = {u, v}, ba_and_more[4] = {b, a, a, u};
        auto good = verify::check_constrained_delaunay2d(p.data(), n, q.data(), nt, ab, 1);
        EXPECT_TRUE(good.ok) << good.message;
        EXPECT_TRUE(
            verify::check_constrained_delaunay2d(p.data(), n, q.data(), nt, ba_and_more, 2).ok);
        auto free_edge =
            verify::check_constrained_delaunay2d(p.data(), n, q.data(), nt, nullptr, 0);
        EXPECT_FALSE(free_edge.ok);
        EXPECT_NE(free_edge.message.find("not locally Delaunay"), std::string::npos)
            << free_edge.message;
        auto crossed = verify::check_constrained_delaunay2d(p.data(), n, q.data(), nt, uv, 1);
        EXPECT_FALSE(crossed.ok);
        EXPECT_NE(crossed.message.find("not a chain of edges"), std::string::npos)
            << crossed.message;
        ++flips;
        break;
      }
  ASSERT_EQ(flips, 3);
  // A segment through a vertex runs along the two edges beside it; bad segments are named.
  const std::vector<double> line{0, 0, 1, 0, 2, 0, 1, 1};
  const std::vector<std::int32_t> tl{0, 1, 3, 1, 2, 3};
  const std::int32_t through[2] = {2, 0}, zero[2] = {3, 3}, outside[2] = {0, 9};
  auto r = verify::check_constrained_delaunay2d(line.data(), 4, tl.data(), 2, through, 1);
  EXPECT_TRUE(r.ok) << r.message;
  EXPECT_NE(r.notes.back().find("2 edges on them"), std::string::npos) << r.notes.back();
  EXPECT_NE(verify::check_constrained_delaunay2d(line.data(), 4, tl.data(), 2, zero, 1)
                .message.find("zero length"),
            std::string::npos);
  EXPECT_NE(verify::check_constrained_delaunay2d(line.data(), 4, tl.data(), 2, outside, 1)
                .message.find("outside"),
            std::string::npos);
}

TEST(Verify, Delaunay3dAcceptsAndRejects) {
  auto p = random_points(3, 18, 2);
  auto t = brute_delaunay3d(p);
  const std::int64_t n = 18, nt = std::int64_t(t.size() / 4);
  auto r = verify::check_delaunay3d(p.data(), n, t.data(), nt);
  ASSERT_TRUE(r.ok) << r.message;
  for (std::int64_t drop : {std::int64_t(0), nt / 2, nt - 1}) {  // a missing tetrahedron
    auto q = t;
    q.erase(q.begin() + 4 * drop, q.begin() + 4 * drop + 4);
    EXPECT_FALSE(verify::check_triangulation3d(p.data(), n, q.data(), nt - 1).ok) << drop;
  }
  {
    auto q = t;
    std::swap(q[0], q[1]);
    EXPECT_FALSE(verify::check_triangulation3d(p.data(), n, q.data(), nt).ok);
  }
  {  // 2-3 flip of an interior face whose edge through the two apexes crosses it: not Delaunay
    bool done = false;
    for (std::int64_t i = 0; i < nt && !done; ++i)
      for (std::int64_t j = 0; j < nt && !done; ++j) {
        if (i == j) continue;
        std::vector<int> a(t.begin() + 4 * i, t.begin() + 4 * i + 4),
            b(t.begin() + 4 * j, t.begin() + 4 * j + 4);
        std::vector<int> common;
        for (int x : a)
          if (std::count(b.begin(), b.end(), x)) common.push_back(x);
        if (common.size() != 3) continue;
        int u = 0, v = 0;
        for (int x : a)
          if (!std::count(common.begin(), common.end(), x)) u = x;
        for (int x : b)
          if (!std::count(common.begin(), common.end(), x)) v = x;
        std::vector<std::int32_t> q;
        bool ok = true;
        for (int k = 0; k < 3 && ok; ++k) {
          int c0 = common[k], c1 = common[(k + 1) % 3];
          int o = pred::orient3d(&p[3 * u], &p[3 * v], &p[3 * c0], &p[3 * c1], S.data());
          if (o == 0) ok = false;
          if (o > 0)
            q.insert(q.end(), {u, v, c0, c1});
          else
            q.insert(q.end(), {u, v, c1, c0});
        }
        // valid 2-3 flip only if segment uv crosses the common triangle
        int s0 = pred::orient3d(&p[3 * common[0]], &p[3 * common[1]], &p[3 * common[2]], &p[3 * u],
                                S.data());
        int s1 = pred::orient3d(&p[3 * common[0]], &p[3 * common[1]], &p[3 * common[2]], &p[3 * v],
                                S.data());
        for (int k = 0; k < 3 && ok; ++k)
          ok = pred::orient3d(&p[3 * u], &p[3 * v], &p[3 * common[k]], &p[3 * common[(k + 1) % 3]],
                              S.data()) ==
               pred::orient3d(&p[3 * u], &p[3 * v], &p[3 * common[1]], &p[3 * common[2]], S.data());
        if (!ok || s0 == s1) continue;
        std::vector<std::int32_t> r2;
        for (std::int64_t k = 0; k < nt; ++k)
          if (k != i && k != j) r2.insert(r2.end(), t.begin() + 4 * k, t.begin() + 4 * k + 4);
        r2.insert(r2.end(), q.begin(), q.end());
        auto tri = verify::check_triangulation3d(p.data(), n, r2.data(), nt + 1);
        if (!tri.ok) continue;
        auto bad = verify::check_delaunay3d(p.data(), n, r2.data(), nt + 1);
        EXPECT_FALSE(bad.ok);
        EXPECT_NE(bad.message.find("not locally Delaunay"), std::string::npos) << bad.message;
        done = true;
      }
    EXPECT_TRUE(done) << "no flippable face found";
  }
}

TEST(Verify, HullAcceptsAndRejects) {
  auto p = random_points(3, 60, 3);
  auto t = brute_hull(p);
  const std::int64_t n = 60, nt = std::int64_t(t.size() / 3);
  auto r = verify::check_hull3d(p.data(), n, t.data(), nt);
  ASSERT_TRUE(r.ok) << r.message;
  {  // missing face
    auto q = t;
    q.resize(q.size() - 3);
    EXPECT_FALSE(verify::check_hull3d(p.data(), n, q.data(), nt - 1).ok);
  }
  {  // a point outside
    auto p2 = p;
    p2.insert(p2.end(), {2.0, 0.5, 0.5});
    auto bad = verify::check_hull3d(p2.data(), n + 1, t.data(), nt);
    EXPECT_FALSE(bad.ok);
    EXPECT_NE(bad.message.find("outside"), std::string::npos) << bad.message;
  }
  {  // reflex edge: flip the diagonal of two adjacent faces
    bool done = false;
    for (std::int64_t i = 0; i < nt && !done; ++i)
      for (std::int64_t j = 0; j < nt && !done; ++j)
        for (int e = 0; e < 3 && !done; ++e)
          for (int f = 0; f < 3 && !done; ++f) {
            int u = t[3 * i + e], v = t[3 * i + (e + 1) % 3], a = t[3 * i + (e + 2) % 3];
            if (t[3 * j + f] != v || t[3 * j + (f + 1) % 3] != u) continue;
            int b = t[3 * j + (f + 2) % 3];
            auto q = t;
            q[3 * i] = a, q[3 * i + 1] = u, q[3 * i + 2] = b;
            q[3 * j] = b, q[3 * j + 1] = v, q[3 * j + 2] = a;
            auto bad = verify::check_hull3d(p.data(), n, q.data(), nt);
            EXPECT_FALSE(bad.ok);
            done = true;
          }
    EXPECT_TRUE(done);
  }
  {  // a non-extreme vertex: the centre of a face, connected as a fan
    auto p2 = p;
    const std::int32_t a = t[0], b = t[1], c = t[2];
    // the midpoint of edge a-b is exactly representable only approximately; use a point on
    // the segment that is exact: a + (b - a) when coordinates are dyadic. Build dyadic copy.
    std::vector<double> d(p.size());
    for (std::size_t i = 0; i < p.size(); ++i)
      d[i] = std::ldexp(std::round(std::ldexp(p[i], 20)), -20);
    auto td = brute_hull(d);
    ASSERT_TRUE(verify::check_hull3d(d.data(), n, td.data(), std::int64_t(td.size() / 3)).ok);
    const std::int32_t x = td[0], y = td[1], z = td[2];
    d.insert(d.end(), {(d[3 * x] + d[3 * y]) / 2, (d[3 * x + 1] + d[3 * y + 1]) / 2,
                       (d[3 * x + 2] + d[3 * y + 2]) / 2});
    // replace face x,y,z by x,m,z and m,y,z, and the neighbour across y-x likewise
    auto q = td;
    const std::int32_t m = std::int32_t(n);
    q[0] = x, q[1] = m, q[2] = z;
    q.insert(q.end(), {m, y, z});
    for (std::size_t k = 3; k < q.size(); k += 3)
      for (int e = 0; e < 3; ++e)
        if (q[k + e] == y && q[k + (e + 1) % 3] == x) {
          const std::int32_t w = q[k + (e + 2) % 3];
          q[k] = y, q[k + 1] = m, q[k + 2] = w;
          q.insert(q.end(), {m, x, w});
          k = q.size();
          break;
        }
    auto bad = verify::check_hull3d(d.data(), n + 1, q.data(), std::int64_t(q.size() / 3));
    EXPECT_FALSE(bad.ok);
    EXPECT_NE(bad.message.find("not extreme"), std::string::npos) << bad.message;
    (void)a, (void)b, (void)c;
  }
}

TEST(Verify, EdtBruteForce) {
  const std::vector<std::int64_t> shape{7, 9};
  const std::vector<std::int64_t> sites{1, 2, 5, 8, 6, 0};
  std::vector<std::int64_t> d(63);
  std::vector<std::int32_t> nn(63);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x) {
      std::int64_t best = 1 << 30;
      for (int s = 0; s < 3; ++s) {
        std::int64_t q = (y - sites[2 * s]) * (y - sites[2 * s]) +
                         (x - sites[2 * s + 1]) * (x - sites[2 * s + 1]);
        if (q < best) best = q, nn[y * 9 + x] = s;
      }
      d[y * 9 + x] = best;
    }
  EXPECT_TRUE(verify::check_edt(shape, sites, d.data(), nn.data()).ok);
  auto d2 = d;
  d2[40] += 1;
  EXPECT_FALSE(verify::check_edt(shape, sites, d2.data(), nn.data()).ok);
  auto n2 = nn;
  n2[0] = (n2[0] + 1) % 3;
  EXPECT_FALSE(verify::check_edt(shape, sites, d.data(), n2.data()).ok);
}
