// The digital 2D Delaunay method (issue 20) on the CPU executor: the same triangles as the
// incremental method on every input, the shifting phase's start a valid triangulation at the
// points' own coordinates, and the sketch used (no fall back) wherever its grid points are exact.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "del2d_cases.hpp"
#include "delaunay2d/digital/digital.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/predicates.hpp"
#include "testing/testing.hpp"

using namespace gpugeom;
namespace dg = gpugeom::del2d::digital;

namespace {

// The start's invariants, checked independently of shift.cpp: counter-clockwise at the points'
// coordinates, each directed edge once, a boundary that turns left or goes straight on.
void expect_valid_start(const std::vector<Point2>& pts, const dg::Start& s) {
  std::set<std::pair<std::int32_t, std::int32_t>> directed;
  for (std::size_t t = 0; t < s.triangles.size(); t += 3) {
    const std::int32_t a = s.triangles[t], b = s.triangles[t + 1], c = s.triangles[t + 2];
    EXPECT_GT(orient2d(pts[std::size_t(a)], pts[std::size_t(b)], pts[std::size_t(c)]), 0)
        << "start triangle " << a << " " << b << " " << c;
    for (auto e : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
      EXPECT_TRUE(directed.insert(e).second) << "edge " << e.first << "-" << e.second << " twice";
  }
  std::map<std::int32_t, std::int32_t> next;
  for (const auto& e : directed)
    if (!directed.count({e.second, e.first})) EXPECT_TRUE(next.emplace(e.first, e.second).second);
  for (const auto& [a, b] : next) {
    const std::int32_t c = next.at(b);
    const int o = orient2d(pts[std::size_t(a)], pts[std::size_t(b)], pts[std::size_t(c)]);
    EXPECT_GE(o, 0) << "the start's boundary turns right at " << b;
  }
}

}  // namespace

TEST(DigitalMethod, SameTrianglesAsIncrementalOnEveryInput) {
  std::int64_t shifted = 0, bad_inner = 0, bad_boundary = 0, missing = 0, fallbacks = 0;
  for (const auto& c : gg_del2d::digital_cases(3000, 21)) {
    SCOPED_TRACE(c.name);
    const std::int64_t n = std::int64_t(c.pts.size());
    Delaunay2dOptions o;
    o.backend = Backend::Cpu;
    const auto inc = delaunay2d(c.pts, o);
    o.method = Method::Digital;
    o.grid = c.grid;
    const auto dig = delaunay2d(c.pts, o);
    gg_del2d::expect_valid(c.pts, dig);
    EXPECT_EQ(gg_del2d::triangle_set(dig), gg_del2d::triangle_set(inc));
    EXPECT_EQ(dig.triangles, inc.triangles);  // (the output's order is the points')
    EXPECT_EQ(dig.neighbors, inc.neighbors);
    EXPECT_EQ(std::vector<std::int32_t>(dig.duplicate_of.begin(), dig.duplicate_of.end()),
              std::vector<std::int32_t>(inc.duplicate_of.begin(), inc.duplicate_of.end()));
    const auto& k = dig.stats;
    // The sketch is used wherever it has a triangle (three sites not on one line).
    const dg::Sketch sk = gpugeom::testing::digital_sketch(
        &c.pts.data()->x, n, c.grid ? c.grid : dg::auto_side(&c.pts.data()->x, n), o);
    const dg::Start st = gpugeom::testing::shift_sketch(&c.pts.data()->x, n, sk, o);
    EXPECT_EQ(st.valid, !sk.triangles.empty()) << st.reason;
    EXPECT_EQ(k.digital_fallback, st.valid ? 0 : 1);
    if (st.valid) {
      expect_valid_start(c.pts, st);
      EXPECT_LE(k.shifted + k.bad_inner + k.bad_boundary, k.sites);
      EXPECT_EQ(k.sites + k.sketch_missing, n);
      EXPECT_EQ(k.start_vertices, st.vertices);
      shifted += k.shifted, bad_inner += k.bad_inner;
      bad_boundary += k.bad_boundary, missing += k.sketch_missing;
    }
    fallbacks += k.digital_fallback;
  }
  // The cases reach both kinds of deletion.
  EXPECT_GT(bad_inner, 0);
  EXPECT_GT(bad_boundary, 0);
  std::printf(
      "digital over the cases: %lld sites shifted, %lld inner and %lld boundary sites deleted, "
      "%lld points sharing a pixel, %lld fall backs (tiny inputs)\n",
      (long long)shifted, (long long)bad_inner, (long long)bad_boundary, (long long)missing,
      (long long)fallbacks);
}

// Sketches whose boundary has three to five vertices: the shifting's tests there read the
// boundary neighbours' neighbours, which are then the site itself or its neighbours (each
// dependency must be counted once on both sides of the wavefront, or a site is never tested and
// the method stops with an internal error). Tiny inputs on coarse grids reach them.
TEST(DigitalMethod, SmallSketchBoundaries) {
  std::int64_t small = 0, cases = 0, no_disk = 0;
  for (int n = 4; n <= 40; n += 3)
    for (std::int64_t side : {4, 6, 8, 16})
      for (int seed = 0; seed < 12; ++seed) {
        std::mt19937_64 r(std::uint64_t(1000 * n + 10 * side + seed));
        std::uniform_real_distribution<double> U(0, 1);
        std::vector<Point2> pts;
        for (int i = 0; i < n; ++i) pts.push_back({U(r), U(r)});
        SCOPED_TRACE("n " + std::to_string(n) + " grid " + std::to_string(side) + " seed " +
                     std::to_string(seed));
        Delaunay2dOptions o;
        o.backend = Backend::Cpu;
        const auto inc = delaunay2d(pts, o);
        o.method = Method::Digital;
        o.grid = side;
        const auto dig = delaunay2d(pts, o);
        EXPECT_EQ(gg_del2d::triangle_set(dig), gg_del2d::triangle_set(inc));
        const dg::Sketch sk = gpugeom::testing::digital_sketch(&pts.data()->x, n, side, o);
        std::int64_t rim = 0;
        for (std::int32_t t : sk.twin) rim += t < 0;
        if (dig.stats.digital_fallback == 0 && rim >= 3 && rim <= 5) ++small;
        // A dual whose boundary passes a vertex twice is no disk: the method says so and runs
        // the incremental one (the same triangles, checked above).
        const std::int64_t pinched = dig.stats.sketch_not_disk;
        if (pinched) EXPECT_EQ(dig.stats.digital_fallback, 1);
        no_disk += pinched;
        ++cases;
      }
  EXPECT_GT(small, 20) << "of " << cases << " cases";
  EXPECT_GT(no_disk, 0) << "no case reached a dual that is no disk";
  std::printf(
      "%lld of %lld small cases shifted a sketch with 3 to 5 boundary vertices; %lld duals were "
      "no disk (fall back)\n",
      (long long)small, (long long)cases, (long long)no_disk);
}

// Grid points that are no exact doubles (coordinates far from 0 against their spread): the
// method says so and runs the incremental one (the same result).
TEST(DigitalMethod, FarFromTheOriginFallsBack) {
  std::vector<Point2> pts;
  std::mt19937_64 r(2);
  std::uniform_real_distribution<double> U(0, 1);
  for (int i = 0; i < 500; ++i) pts.push_back({1e17 + 65536 * U(r), 1e-3 * U(r)});
  Delaunay2dOptions o;
  o.backend = Backend::Cpu;
  const auto inc = delaunay2d(pts, o);
  o.method = Method::Digital;
  const auto dig = delaunay2d(pts, o);
  EXPECT_EQ(dig.stats.digital_fallback, 1);
  EXPECT_EQ(gg_del2d::triangle_set(dig), gg_del2d::triangle_set(inc));
}

TEST(DigitalMethod, RefusesWhatItCannotDo) {
  std::vector<Point2> pts{{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  Delaunay2dOptions o;
  o.backend = Backend::Cpu;
  o.method = Method::Digital;
  o.grid = 3;
  EXPECT_THROW(delaunay2d(pts, o), Error);
  o.grid = 0;
  EXPECT_THROW(delaunay2d_device(&pts.data()->x, 4, o), Error);
  pts.push_back({std::nan(""), 0});
  try {
    delaunay2d(pts, o);
    ADD_FAILURE() << "NaN accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidInput);
  }
  EXPECT_EQ(parse_method("Digital"), Method::Digital);
  EXPECT_THROW(parse_method("magic"), Error);
}
