// DigiDel3D (Delaunay3dOptions::method = Method::Digital) on the CPU executor: the same
// tetrahedra as the incremental method on every distribution and degenerate input, on the
// automatic grid and on grids too coarse and too fine for the input, valid by the exact checker,
// and its errors.
#include <cstdio>
#include <string>

#include "del3d_cases.hpp"

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
  const bool fell_back = dig.stats.counters.at("digital_fallback") != 0;
  if (!fell_back) EXPECT_GT(dig.stats.counters.at("digital_splay_rounds"), 0);
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
  EXPECT_LT(delaunay3d(turned, o).stats.counters.at("digital_points_on_box"), 4096);
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
  const auto& k = t.stats.counters;
  EXPECT_EQ(k.at("digital_grid"), 86);  // (cube root of 32 points' cells, rounded)
  EXPECT_EQ(k.at("sites") + k.at("sketch_missing"), 20000);
  EXPECT_GT(k.at("digital_working_pairs"), 20000);
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
  ASSERT_EQ(dev.num_tetrahedra, std::int64_t(host.num_tetrahedra()));
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
  o.max_flip_rounds = 1;
  EXPECT_THROW(delaunay3d(pts, o), Error);
  // Too few distinct points: the same error as the incremental method's.
  const std::vector<Point3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 2, 0}};
  EXPECT_THROW(delaunay3d(flat, cpu(Method::Digital)), Error);
}
