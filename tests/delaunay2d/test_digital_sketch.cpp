// The digital sketch of the 2D Delaunay triangulation (issue 20, Phases 1a and 1b): the
// recoloured digital Voronoi diagram equals the standard flooding algorithm's colouring (thesis
// 4.3.6), every cell is 8-connected to its site, and the dual is a valid triangulation of the
// sites at their grid points (counter-clockwise triangles, each directed edge once).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <queue>
#include <tuple>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "del2d_cases.hpp"
#include "gpugeom/cdt2d.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/predicates.hpp"
#include "testing/testing.hpp"

using namespace gpugeom;
namespace dg = gpugeom::del2d::digital;

namespace {

struct Case {
  std::string name;
  std::vector<double> xy;
  std::int64_t side;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  std::mt19937_64 r(3);
  std::uniform_real_distribution<double> U(0, 1);
  std::normal_distribution<double> N(0, 1);
  for (std::int64_t n : {3, 20, 200, 2000})
    for (std::int64_t side : {16, 64, 256}) {
      Case c{"uniform " + std::to_string(n) + " on " + std::to_string(side), {}, side};
      for (std::int64_t i = 0; i < n; ++i) c.xy.insert(c.xy.end(), {U(r), U(r)});
      out.push_back(c);
    }
  for (std::int64_t side : {32, 128}) {  // clusters: many points per pixel, thin cells, debris
    Case c{"clusters on " + std::to_string(side), {}, side};
    for (int k = 0; k < 12; ++k) {
      const double cx = U(r), cy = U(r), sd = 0.002 + 0.03 * U(r);
      for (int i = 0; i < 150; ++i) c.xy.insert(c.xy.end(), {cx + sd * N(r), cy + sd * N(r)});
    }
    out.push_back(c);
  }
  {
    Case c{"lattice (ties everywhere)", {}, 61};
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 12; ++x) c.xy.insert(c.xy.end(), {double(x), double(y)});
    out.push_back(c);
  }
  {
    Case c{"thin circle", {}, 200};
    for (int i = 0; i < 500; ++i) {
      const double a = 2 * 3.141592653589793 * i / 500, rr = 1 + 0.001 * U(r);
      c.xy.insert(c.xy.end(), {rr * std::cos(a), rr * std::sin(a)});
    }
    out.push_back(c);
  }
  return out;
}

// The standard flooding algorithm (thesis Alg. 4.2), the oracle: every site's region grows
// from its pixel over 8-neighbours, pixels taken in the order (squared distance to the site,
// the site's raster index, the pixel's raster index). Returns the site index per pixel.
std::vector<std::int32_t> standard_flooding(std::int64_t w, std::int64_t h,
                                            const std::vector<std::int32_t>& site_pixel) {
  // (squared distance, the site's pixel, the pixel, the site)
  using Item = std::tuple<std::int64_t, std::int32_t, std::int32_t, std::int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  auto d2 = [&](std::int32_t p, std::int32_t s) {
    const std::int64_t dx = p % w - s % w, dy = p / w - s / w;
    return dx * dx + dy * dy;
  };
  for (std::size_t s = 0; s < site_pixel.size(); ++s)
    q.push({0, site_pixel[s], site_pixel[s], std::int32_t(s)});
  std::vector<std::int32_t> colour(std::size_t(w * h), -1);
  while (!q.empty()) {
    const auto [d, sp, p, s] = q.top();
    q.pop();
    if (colour[std::size_t(p)] >= 0) continue;
    colour[std::size_t(p)] = s;
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        const std::int64_t x = p % w + dx, y = p / w + dy;
        if ((dx || dy) && x >= 0 && y >= 0 && x < w && y < h &&
            colour[std::size_t(y * w + x)] < 0) {
          const std::int32_t b = std::int32_t(y * w + x);
          q.push({d2(b, sp), sp, b, s});
        }
      }
  }
  return colour;
}

// Do segments a-b and c-d cross at a point inside both? (exact)
bool gg_test_cross(const std::vector<double>& p, std::int32_t a, std::int32_t b, std::int32_t c,
                   std::int32_t d) {
  auto o = [&](std::int32_t i, std::int32_t j, std::int32_t k) {
    return orient2d(Point2{p[2 * i], p[2 * i + 1]}, Point2{p[2 * j], p[2 * j + 1]},
                    Point2{p[2 * k], p[2 * k + 1]});
  };
  return o(a, b, c) * o(a, b, d) < 0 && o(c, d, a) * o(c, d, b) < 0;
}

}  // namespace

TEST(DigitalSketch, RecolouredDiagramIsTheStandardFloodingAndItsDualIsATriangulation) {
  std::int64_t debris = 0, pinched = 0, hull_added = 0;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const std::int64_t n = std::int64_t(c.xy.size() / 2);
    RunOptions run;
    run.backend = Backend::Cpu;
    const dg::Sketch s = gpugeom::testing::digital_sketch(c.xy.data(), n, c.side, run, true);
    const std::int64_t w = s.width, h = s.height;
    EXPECT_TRUE(s.exact);
    EXPECT_LE(std::max(w, h), c.side + 2);
    EXPECT_GE(2 * std::max(w, h), c.side) << "the grid uses less than half the side";
    // Every point lies in its pixel: ox + gx h <= x < ox + (gx + 1) h (h a power of two, the
    // origin a multiple of it: all exact).
    for (std::int64_t i = 0; i < n; ++i) {
      const double gx = double(s.pixel[std::size_t(i)] % w),
                   gy = double(s.pixel[std::size_t(i)] / w);
      EXPECT_TRUE(s.ox + gx * s.h <= c.xy[2 * i] && c.xy[2 * i] < s.ox + (gx + 1) * s.h) << i;
      EXPECT_TRUE(s.oy + gy * s.h <= c.xy[2 * i + 1] && c.xy[2 * i + 1] < s.oy + (gy + 1) * s.h);
    }
    debris += s.debris;
    pinched += s.pinched;
    hull_added += s.hull_triangles;
    // Sites: the first point of each pixel; the others missing.
    std::map<std::int32_t, std::int32_t> site_of_pixel;
    std::vector<std::int32_t> site_pixels, site_points;
    std::vector<char> is_missing(std::size_t(n), 0);
    for (std::int32_t m : s.missing) is_missing[std::size_t(m)] = 1;
    for (std::int32_t i = 0; i < n; ++i) {
      const std::int32_t p = s.pixel[std::size_t(i)];
      const bool first = site_of_pixel.emplace(p, i).second;
      EXPECT_EQ(first, !is_missing[std::size_t(i)]) << "point " << i;
      if (first) site_pixels.push_back(p), site_points.push_back(i);
    }
    // The colouring equals the standard flooding's.
    const auto ref = standard_flooding(w, h, site_pixels);
    std::int64_t differ = 0;
    for (std::size_t p = 0; p < ref.size(); ++p)
      differ += s.colour[p] != site_points[std::size_t(ref[p])];
    EXPECT_EQ(differ, 0) << "pixels coloured unlike the standard flooding";
    // The dual: counter-clockwise triangles of sites at their grid points, each directed edge
    // once, every site a vertex when there are three sites or more.
    auto gx = [&](std::int32_t i) { return std::int64_t(s.pixel[std::size_t(i)] % w); };
    auto gy = [&](std::int32_t i) { return std::int64_t(s.pixel[std::size_t(i)] / w); };
    std::set<std::pair<std::int32_t, std::int32_t>> directed;
    std::set<std::int32_t> used;
    for (std::size_t t = 0; t < s.triangles.size(); t += 3) {
      const std::int32_t a = s.triangles[t], b = s.triangles[t + 1], d = s.triangles[t + 2];
      const std::int64_t o = (gx(b) - gx(a)) * (gy(d) - gy(a)) - (gy(b) - gy(a)) * (gx(d) - gx(a));
      EXPECT_GT(o, 0) << "triangle " << a << " " << b << " " << d << " is not counter-clockwise";
      for (auto e : {std::pair{a, b}, std::pair{b, d}, std::pair{d, a}})
        EXPECT_TRUE(directed.insert(e).second) << "edge " << e.first << "-" << e.second << " twice";
      used.insert({a, b, d});
    }
    // The triangles cover a disk: no hole, one piece (V - E + F = 1), with a convex boundary
    // (each boundary vertex turns left or goes straight).
    if (!s.triangles.empty()) {
      std::map<std::int32_t, std::int32_t> next;
      for (const auto& e : directed)
        if (!directed.count({e.second, e.first})) next[e.first] = e.second;
      for (const auto& [a, b] : next) {
        const std::int32_t c = next.at(b);
        const std::int64_t o =
            (gx(b) - gx(a)) * (gy(c) - gy(a)) - (gy(b) - gy(a)) * (gx(c) - gx(a));
        EXPECT_GE(o, 0) << "the boundary turns right at " << b;
      }
      std::set<std::pair<std::int32_t, std::int32_t>> undirected;
      for (const auto& e : directed)
        undirected.insert({std::min(e.first, e.second), std::max(e.first, e.second)});
      const std::int64_t chi = std::int64_t(used.size()) - std::int64_t(undirected.size()) +
                               std::int64_t(s.triangles.size() / 3);
      EXPECT_EQ(chi, 1) << "the dual is not a disk (V - E + F = " << chi << ")";
    }
    // A site in no triangle has a cell on the grid's border: the dual of a truncated diagram
    // misses only such sites (the hull completion and the missing points' insertion take them).
    std::set<std::int32_t> on_border;
    for (std::int64_t k = 0; k < w; ++k)
      for (std::int64_t p : {k, (h - 1) * w + k}) on_border.insert(s.colour[std::size_t(p)]);
    for (std::int64_t k = 0; k < h; ++k)
      for (std::int64_t p : {k * w, k * w + w - 1}) on_border.insert(s.colour[std::size_t(p)]);
    for (std::int32_t i : site_points)
      if (!used.count(i) && site_points.size() >= 3)
        EXPECT_TRUE(on_border.count(i)) << "site " << i << " is in no triangle, inside the grid";
  }
  EXPECT_GT(debris, 0);  // (the cases exercise the recolouring)
  EXPECT_GT(hull_added, 0);
  std::printf(
      "over the cases: %lld debris pixels recoloured, %lld pinched corners, %lld hull "
      "triangles\n",
      static_cast<long long>(debris), static_cast<long long>(pinched),
      static_cast<long long>(hull_added));
}

// The 2D Triangulator started from a given triangulation (the digital method's entry into the
// shared batches and flip rounds): a Delaunay or a constrained (non-Delaunay) triangulation of
// some of the points; the others inserted and the whole flipped: the same triangles as the
// incremental method's, on random points with duplicates and on an integer lattice.
TEST(DigitalSketch, TriangulatorFromAStartEqualsIncremental) {
  std::mt19937_64 r(11);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<std::vector<double>> inputs(2);
  for (int i = 0; i < 3000; ++i) inputs[0].insert(inputs[0].end(), {U(r), U(r)});
  for (int i = 0; i < 40; ++i)
    inputs[0].insert(inputs[0].end(), {inputs[0][2 * i], inputs[0][2 * i + 1]});
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x)
      inputs[1].insert(inputs[1].end(), {double((x * 17) % 40), double(y)});
  for (const auto& xy : inputs) {
    const std::int64_t n = std::int64_t(xy.size() / 2), k = n / 8;
    Delaunay2dOptions o;
    o.backend = Backend::Cpu;
    const auto whole = delaunay2d(xy.data(), n, o);
    const auto ref =
        gg_del2d::triangle_set(whole.triangles.data(), std::size_t(whole.num_triangles));
    // Starts: the Delaunay triangulation of the first k points, and a constrained one of them
    // (segments between far points: many of its edges are not Delaunay).
    std::vector<std::vector<std::int32_t>> starts;
    const auto part = delaunay2d(xy.data(), k, o);
    starts.emplace_back(part.triangles.begin(), part.triangles.end());
    std::vector<std::int32_t> segs;
    for (std::int32_t i = 0; i + 1 < std::int32_t(k) && segs.size() < 40; i += 7) {
      const std::int32_t a = i, b = std::int32_t((i * 31 + 5) % k);
      bool ok = a != b;
      for (std::size_t s = 0; s < segs.size() && ok; s += 2)
        ok = !gg_test_cross(xy, a, b, segs[s], segs[s + 1]);
      if (ok) segs.insert(segs.end(), {a, b});
    }
    Cdt2dOptions co;
    co.backend = Backend::Cpu;
    const auto c = cdt2d(xy.data(), k, segs.data(), std::int64_t(segs.size() / 2), co);
    EXPECT_GT(c.stats.segments_recovered, 0);
    starts.emplace_back(c.triangles.begin(), c.triangles.end());
    // Walk hints (a start vertex per point, where its walk begins) change nothing but the walks.
    std::vector<std::int32_t> hint(static_cast<std::size_t>(n));
    for (std::int64_t i = 0; i < n; ++i) hint[std::size_t(i)] = std::int32_t((i * 13) % k);
    for (const auto& s : starts)
      for (const std::int32_t* h : std::vector<const std::int32_t*>{nullptr, hint.data()}) {
        del2d::Output out;
        Delaunay2dStats st;
        gpugeom::testing::triangulate_from(xy.data(), n, s.data(), std::int64_t(s.size() / 3),
                                           nullptr, h, o, out, st);
        EXPECT_EQ(gg_del2d::triangle_set(out.triangles.data(), std::size_t(out.num_triangles)),
                  ref);
        EXPECT_EQ(out.duplicate_of, whole.duplicate_of);
      }
  }
}
