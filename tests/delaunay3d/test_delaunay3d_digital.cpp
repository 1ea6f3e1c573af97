// DigiDel3D (Delaunay3dOptions::method = Method::Digital) on the CPU executor: the same
// tetrahedra as the incremental method on every distribution and degenerate input, on the
// automatic grid and on grids too coarse and too fine for the input, valid by the exact checker,
// and its errors.
#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "del3d_cases.hpp"
#include "../common/tuning.hpp"
#include "gpugeom/predicates.hpp"
#include "testing/testing.hpp"

using namespace gpugeom;
using gg_del3d::expect_valid;
using gg_del3d::tet_set;

namespace {
Delaunay3dOptions cpu(Method m = Method::Incremental, std::int64_t grid = 0) {
  Delaunay3dOptions o;
  o.backend = Backend::Cpu;
  o.method = m;
  o.grid = grid;
  return o;
}

// Returns whether the digital method fell back to the incremental one (stars too large).
bool same_as_incremental(const gg_hull3d::Case& c, std::int64_t grid) {
  SCOPED_TRACE(c.name + ", grid " + std::to_string(grid));
  const auto inc = delaunay3d(c.pts, cpu());
  const auto dig = delaunay3d(c.pts, cpu(Method::Digital, grid));
  expect_valid(c.pts, dig);
  EXPECT_EQ(tet_set(dig.tetrahedra), tet_set(inc.tetrahedra));
  EXPECT_EQ(dig.num_duplicates, inc.num_duplicates);
  EXPECT_EQ(dig.hull_facets.size(), inc.hull_facets.size());
  const bool fell_back = dig.stats.digital_fallback != 0;
  if (!fell_back) EXPECT_GT(dig.stats.digital_splay_rounds, 0);
  return fell_back;
}
bool is(const gg_hull3d::Case& c, const char* prefix) {
  return c.name.rfind(prefix, 0) == 0;
}
}  // namespace

TEST(DigitalDelaunay3d, SameAsIncrementalOnDistributions) {
  for (const auto& c : gg_hull3d::distribution_cases({5, 10, 100, 1000, 10000}, 3)) {
    if (is(c, "two_lines") && c.pts.size() > 100) continue;  // (quadratic)
    const bool fell_back = same_as_incremental(c, 0);
    // Only the grid's hull-plane stars may grow past what the executor splays.
    if (!is(c, "grid") && !is(c, "two_lines")) EXPECT_FALSE(fell_back) << c.name;
  }
}

TEST(DigitalDelaunay3d, SameAsIncrementalOnDegenerateInput) {
  int fell_back = 0, cases = 0;
  for (const auto& c : gg_hull3d::degenerate_cases())
    fell_back += same_as_incremental(c, 0), ++cases;
  std::printf("%d of %d degenerate cases fell back to the incremental method\n", fell_back, cases);
  EXPECT_LT(fell_back, cases / 2);
}

// The hull planes of an integer grid give stars of thousands of triangles while splaying, which
// the executor does not splay (kHugeStar): the method falls back to the incremental one.
TEST(DigitalDelaunay3d, GridHullPlanesFallBack) {
  // On the box's planes: found before any star is built.
  const gg_hull3d::Case c{"grid_30000", generate3d("grid", 30000, 3)};
  EXPECT_TRUE(same_as_incremental(c, 0));
  // Turned about z by an exact rotation (3/5, 4/5; coordinates times 5 stay whole), four of the
  // hull planes are on no plane of the box: the stars grow until one passes kHugeStar.
  std::vector<Point3> turned;
  for (int x = 0; x < 31; ++x)
    for (int y = 0; y < 31; ++y)
      for (int z = 0; z < 31; ++z)
        turned.push_back({3.0 * x - 4.0 * y, 4.0 * x + 3.0 * y, 5.0 * z});
  const gg_hull3d::Case t{"turned_grid_29791", turned};
  EXPECT_TRUE(same_as_incremental(t, 0));
  Delaunay3dOptions o = cpu(Method::Digital);
  EXPECT_LT(delaunay3d(turned, o).stats.digital_points_on_box, 4096);
}

// A coarse grid leaves most points missing (their stars start from their site's set) and a
// fine one leaves cells empty between sites: the stars then start far from right, and
// splaying must do the rest.
TEST(DigitalDelaunay3d, SameOnCoarseAndFineGrids) {
  for (const char* d : {"uniform", "gaussian", "thin_sphere", "grid"}) {
    const gg_hull3d::Case c{std::string(d) + "_3000", generate3d(d, 3000, 11)};
    for (std::int64_t g : {16, 24, 128}) same_as_incremental(c, g);
  }
}

TEST(DigitalDelaunay3d, PhasesAndCounters) {
  const auto pts = generate3d("uniform", 20000, 5);
  const auto t = delaunay3d(pts, cpu(Method::Digital));
  expect_valid(pts, t);
  const auto& k = t.stats;
  EXPECT_EQ(k.digital_grid, 86);  // (cube root of 32 points' cells, rounded)
  EXPECT_EQ(k.sites + k.sketch_missing, 20000);
  EXPECT_GT(k.digital_working_pairs, 20000);
  std::set<std::string> phases;
  for (const auto& p : t.stats.phase_ms) phases.insert(p.first);
  for (const char* p : {"prepare", "digital_grid", "digital_pba", "digital_working_sets",
                        "digital_stars", "digital_splay", "digital_tetrahedra", "output"})
    EXPECT_TRUE(phases.count(p)) << p;
}

TEST(DigitalDelaunay3d, DeviceEntryOnTheCpuExecutor) {
  const auto pts = generate3d("gaussian", 5000, 2);
  const auto host = delaunay3d(pts, cpu(Method::Digital));
  const auto dev =
      delaunay3d_device(&pts.data()->x, std::int64_t(pts.size()), cpu(Method::Digital));
  ASSERT_EQ(dev.num_tetrahedra, host.num_tetrahedra);
  std::vector<std::int32_t> t(dev.tetrahedra.get(), dev.tetrahedra.get() + 4 * dev.num_tetrahedra);
  EXPECT_EQ(tet_set(t), tet_set(host.tetrahedra));
}

TEST(DigitalDelaunay3d, Errors) {
  const auto pts = generate3d("uniform", 100, 1);
  for (std::int64_t g : {-1, 8, 15, 1025}) {
    try {
      delaunay3d(pts, cpu(Method::Digital, g));
      ADD_FAILURE() << "grid " << g << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
      EXPECT_NE(std::string(e.what()).find("16..1024"), std::string::npos) << e.what();
    }
  }
  try {
    delaunay3d(pts, cpu(Method::Incremental, 64));
    ADD_FAILURE() << "grid without the digital method accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
  }
  Delaunay3dOptions o = cpu(Method::Digital);
  o.tuning = gg_test::tuning([&](detail::Tuning& t) { t.del3d.max_flip_rounds = 1; });
  EXPECT_THROW(delaunay3d(pts, o), Error);
  // Too few distinct points: the same error as the incremental method's.
  const std::vector<Point3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 2, 0}};
  EXPECT_THROW(delaunay3d(flat, cpu(Method::Digital)), Error);
}

// The stars on their own, checked here with the public exact predicates (simulation of
// simplicity by the perturbation's order): after creation each star is a closed, oriented,
// convex link around its point; after splaying every tetrahedron of a star is in the stars of
// its other points, and the finite ones with positive volume are the incremental method's.
namespace {
using Stars = gpugeom::testing::Stars;

struct StarView {
  const Stars& s;
  std::int32_t m;
  Point3 at(std::int32_t i) const {
    return {s.pts[3 * std::size_t(i)], s.pts[3 * std::size_t(i) + 1],
            s.pts[3 * std::size_t(i) + 2]};
  }
  std::vector<std::array<std::int32_t, 3>> star(std::int32_t v) const {
    std::vector<std::array<std::int32_t, 3>> r;
    for (std::int64_t t = s.start[std::size_t(v)]; t < s.start[std::size_t(v) + 1]; ++t)
      r.push_back({s.tri[3 * std::size_t(t)], s.tri[3 * std::size_t(t) + 1],
                   s.tri[3 * std::size_t(t) + 2]});
    return r;
  }
  // Is d inside the sphere of the positive tetrahedron (v, a, b, c)? (With the infinity point
  // among them, the half-space beyond the finite face; the infinity point is inside none.)
  bool inside(std::int32_t v, std::array<std::int32_t, 3> t, std::int32_t d) const {
    if (d == m) return false;
    std::array<std::int32_t, 4> q{v, t[0], t[1], t[2]};
    for (auto& x : q)
      if (x == m) {
        x = d;
        return orient3d_sos(at(q[0]), q[0], at(q[1]), q[1], at(q[2]), q[2], at(q[3]), q[3]) > 0;
      }
    return insphere_sos(at(q[0]), q[0], at(q[1]), q[1], at(q[2]), q[2], at(q[3]), q[3], at(d), d) >
           0;
  }
};

void expect_closed_convex_stars(const Stars& s) {
  const StarView V{s, std::int32_t(s.pts.size() / 3)};
  for (std::int32_t v = 0; v < V.m; ++v) {
    const auto st = V.star(v);
    ASSERT_GE(st.size(), 4u) << "star " << v;
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> opposite;  // edge -> third
    for (const auto& t : st)
      for (int k = 0; k < 3; ++k) {
        const auto e = std::make_pair(t[std::size_t(k)], t[std::size_t(k + 1) % 3]);
        ASSERT_EQ(opposite.count(e), 0u) << "star " << v << ": a link edge twice";
        opposite[e] = t[std::size_t(k + 2) % 3];
        if (t[0] != V.m && t[1] != V.m && t[2] != V.m)
          ASSERT_GT(orient3d_sos(V.at(v), v, V.at(t[0]), t[0], V.at(t[1]), t[1], V.at(t[2]), t[2]),
                    0)
              << "star " << v << ": a triangle not positive";
      }
    for (const auto& t : st)
      for (int k = 0; k < 3; ++k) {
        const auto back = std::make_pair(t[std::size_t(k + 1) % 3], t[std::size_t(k)]);
        ASSERT_EQ(opposite.count(back), 1u) << "star " << v << ": the link is not closed";
        ASSERT_FALSE(V.inside(v, t, opposite[back])) << "star " << v << ": a reflex link edge";
      }
  }
}
}  // namespace

TEST(DigitalDelaunay3d, StarsOnTheirOwn) {
  for (const char* d : {"uniform", "gaussian", "thin_sphere"}) {
    SCOPED_TRACE(d);
    const auto pts = generate3d(d, 2000, 9);
    // (splay 2: the tetrahedra's rounds and the proof alone, which the vertex rounds leave
    // little to do)
    for (int splay : {0, 1, 2}) {
      SCOPED_TRACE(splay);
      const bool splayed = splay > 0;
      Stars s;
      gpugeom::testing::digital_stars(&pts.data()->x, 2000, 0, splay, s);
      ASSERT_TRUE(s.built);
      expect_closed_convex_stars(s);
      const StarView V{s, std::int32_t(s.pts.size() / 3)};
      std::int64_t lacking = 0;  // tetrahedra some other star lacks
      for (std::int32_t v = 0; v < V.m; ++v)
        for (const auto& t : V.star(v))
          for (int k = 0; k < 3; ++k) {
            const std::int32_t w = t[std::size_t(k)];
            if (w == V.m) continue;
            std::array<std::int32_t, 3> o{v, t[std::size_t(k + 1) % 3], t[std::size_t(k + 2) % 3]};
            std::sort(o.begin(), o.end());
            bool found = false;
            for (auto u : V.star(w)) {
              std::sort(u.begin(), u.end());
              found = found || u == o;
            }
            lacking += !found;
          }
      if (!splayed) {  // the working sets miss neighbours: the first stars disagree
        EXPECT_GT(lacking, 0);
        continue;
      }
      EXPECT_EQ(lacking, 0);
      std::set<std::array<std::int32_t, 4>> finite;
      for (std::int32_t v = 0; v < V.m; ++v)
        for (const auto& t : V.star(v)) {
          if (t[0] == V.m || t[1] == V.m || t[2] == V.m) continue;
          if (orient3d(V.at(v), V.at(t[0]), V.at(t[1]), V.at(t[2])) == 0) continue;  // flat
          std::array<std::int32_t, 4> q{v, t[0], t[1], t[2]};
          std::sort(q.begin(), q.end());
          finite.insert(q);
        }
      // The incremental method's tetrahedra, in the same (curve) order: through the points.
      const auto inc = delaunay3d(pts, cpu());
      std::map<std::array<double, 3>, std::int32_t> index;
      for (std::int32_t i = 0; i < V.m; ++i) index[{V.at(i).x, V.at(i).y, V.at(i).z}] = i;
      std::set<std::array<std::int32_t, 4>> want;
      for (std::size_t c = 0; c < inc.tetrahedra.size() / 4; ++c) {
        std::array<std::int32_t, 4> q;
        for (int k = 0; k < 4; ++k) {
          const Point3& p = pts[std::size_t(inc.tetrahedra[4 * c + std::size_t(k)])];
          q[std::size_t(k)] = index.at({p.x, p.y, p.z});
        }
        std::sort(q.begin(), q.end());
        want.insert(q);
      }
      EXPECT_EQ(finite, want);
    }
  }
}

// The vertex tables (each link vertex once, with a hash of its ring) follow their stars through
// creation, takes and growth: the checks pass a pair on equal hashes, so a table out of date
// would not change the result (the proof looks up every tetrahedron) but would cost rounds,
// which no result shows. Checked against the rings read off the triangles: every link vertex
// is listed once and nothing else; equal rings around an edge have equal hashes (every edge
// after splaying), and different rings different ones (after creation, where many differ).
namespace {
using Ring = std::set<std::int32_t>;
std::map<std::int32_t, Ring> rings(const StarView& V, std::int32_t v) {
  std::map<std::int32_t, Ring> r;
  for (const auto& t : V.star(v))
    for (int k = 0; k < 3; ++k) {
      r[t[std::size_t(k)]].insert(t[std::size_t(k + 1) % 3]);
      r[t[std::size_t(k)]].insert(t[std::size_t(k + 2) % 3]);
    }
  return r;
}
std::map<std::int32_t, std::uint32_t> table(const Stars& s, std::int32_t v) {
  std::map<std::int32_t, std::uint32_t> r;
  for (std::int64_t j = s.table_start[std::size_t(v)]; j < s.table_start[std::size_t(v) + 1]; ++j) {
    EXPECT_EQ(r.count(s.table_vertex[std::size_t(j)]), 0u) << "star " << v << ": listed twice";
    r[s.table_vertex[std::size_t(j)]] = s.table_hash[std::size_t(j)];
  }
  return r;
}
}  // namespace

TEST(DigitalDelaunay3d, VertexTablesFollowTheStars) {
  for (const char* d : {"uniform", "gaussian", "thin_sphere"}) {
    SCOPED_TRACE(d);
    const auto pts = generate3d(d, 2000, 5);
    for (int splay : {0, 1}) {
      SCOPED_TRACE(splay);
      Stars s;
      gpugeom::testing::digital_stars(&pts.data()->x, 2000, 0, splay, s);
      ASSERT_TRUE(s.built);
      const StarView V{s, std::int32_t(s.pts.size() / 3)};
      std::vector<std::map<std::int32_t, Ring>> R(std::size_t(V.m));
      std::vector<std::map<std::int32_t, std::uint32_t>> H(std::size_t(V.m));
      for (std::int32_t v = 0; v < V.m; ++v) {
        R[std::size_t(v)] = rings(V, v);
        H[std::size_t(v)] = table(s, v);
        ASSERT_EQ(H[std::size_t(v)].size(), R[std::size_t(v)].size()) << "star " << v;
        for (const auto& [x, ring] : R[std::size_t(v)])
          ASSERT_EQ(H[std::size_t(v)].count(x), 1u) << "star " << v << " lacks " << x;
      }
      std::int64_t same = 0, differ = 0;
      for (std::int32_t v = 0; v < V.m; ++v)
        for (const auto& [u, ring] : R[std::size_t(v)]) {
          if (u == V.m || u < v || !R[std::size_t(u)].count(v)) continue;
          const bool equal_rings = ring == R[std::size_t(u)].at(v);
          const bool equal_hashes = H[std::size_t(v)].at(u) == H[std::size_t(u)].at(v);
          EXPECT_EQ(equal_hashes, equal_rings) << "edge " << v << "-" << u;
          (equal_rings ? same : differ) += 1;
        }
      EXPECT_GT(same, 0);
      if (splay == 1)
        EXPECT_EQ(differ, 0);  // (the stars agree)
      else
        EXPECT_GT(differ, 0);  // (the first stars disagree: the test sees different rings)
    }
  }
}

// Requests past the splaying's request buffer: those that fit stay and the threads that lost
// some run again (not the whole round); the stars come out the same as with room for all.
TEST(DigitalDelaunay3d, RequestsPastTheBuffer) {
  for (const char* d : {"uniform", "thin_sphere"}) {
    SCOPED_TRACE(d);
    const auto pts = generate3d(d, 2000, 6);
    Stars roomy, tight;
    gpugeom::testing::digital_stars(&pts.data()->x, 2000, 0, 1, roomy);
    gpugeom::testing::digital_stars(&pts.data()->x, 2000, 0, 1, tight, 64);
    ASSERT_TRUE(roomy.built && tight.built);
    EXPECT_EQ(roomy.request_spills, 0);
    EXPECT_GT(tight.request_spills, 0);
    const StarView A{roomy, std::int32_t(roomy.pts.size() / 3)}, B{tight, A.m};
    // (each star as its triangles, each turned to start at its lowest vertex, sorted)
    auto norm = [](std::vector<std::array<std::int32_t, 3>> st) {
      for (auto& t : st) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      std::sort(st.begin(), st.end());
      return st;
    };
    for (std::int32_t v = 0; v < A.m; ++v) ASSERT_EQ(norm(A.star(v)), norm(B.star(v))) << v;
  }
}
