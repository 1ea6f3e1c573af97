// Every capability called from several host threads at once, each call with options of its own
// (thread counts, methods and the library's internal knobs: RunOptions::tuning), on the executor
// this binary is built for. Each result must equal the one a lone call with default options
// gives: the library keeps no state between calls that one call could change for another (issue
// 48: no global mutable state), and no knob or thread count changes a result.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "../common/on_host_threads.hpp"
#include "../common/tuning.hpp"
#include "gpugeom/cdt2d.hpp"
#include "gpugeom/cvd.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/delaunay3d.hpp"
#include "gpugeom/edt.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/hull3d.hpp"
#include "gpugeom/locate.hpp"
#include "gpugeom/refine2d.hpp"
#include "gpugeom/voronoi3d.hpp"
#include "gpugeom/voronoi_cells.hpp"

#ifndef GG_CONCURRENCY_BACKEND
#define GG_CONCURRENCY_BACKEND Cpu
#endif

using namespace gpugeom;
using detail::Tuning;

namespace {

constexpr Backend kBackend = Backend::GG_CONCURRENCY_BACKEND;

// A result as the bytes of its arrays, in order, with a name for each (so that a difference
// names the array it is in).
struct Arrays {
  std::vector<std::pair<std::string, std::string>> parts;
  template <class V>
  Arrays& add(const std::string& name, const V& v) {
    std::string bytes(v.size() * sizeof(v.data()[0]), '\0');
    if (!bytes.empty()) std::memcpy(bytes.data(), v.data(), bytes.size());
    parts.emplace_back(name, std::move(bytes));
    return *this;
  }
};

void expect_same(const std::string& job, const Arrays& want, const Arrays& got) {
  ASSERT_EQ(want.parts.size(), got.parts.size()) << job;
  for (std::size_t i = 0; i < want.parts.size(); ++i)
    EXPECT_TRUE(want.parts[i].second == got.parts[i].second)
        << job << ": " << want.parts[i].first << " differs (" << want.parts[i].second.size()
        << " bytes wanted, " << got.parts[i].second.size() << " got)";
}

// The triangles or tetrahedra as a sorted list of sorted vertex tuples: for calls whose knob may
// change the order of the simplices but not the simplices (fewer flip rounds, repaired after).
template <std::size_t K>
std::vector<std::array<std::int32_t, K>> simplex_set(const std::vector<std::int32_t>& s) {
  std::vector<std::array<std::int32_t, K>> out(s.size() / K);
  for (std::size_t i = 0; i < out.size(); ++i) {
    std::copy(s.begin() + std::ptrdiff_t(K * i), s.begin() + std::ptrdiff_t(K * i + K),
              out[i].begin());
    std::sort(out[i].begin(), out[i].end());
  }
  std::sort(out.begin(), out.end());
  return out;
}

template <class Options>
Options on_backend(int threads, Options o = {}) {
  o.backend = kBackend;
  o.threads = threads;
  return o;
}

// One call: its name and the result of the call with options variant k (k = 0: the defaults,
// one CPU thread, no knobs).
struct Job {
  std::string name;
  std::function<Arrays(int)> run;
};

std::vector<Job> jobs() {
  std::vector<Job> J;
  const auto p2 = generate2d("uniform", 20000, 3);
  const auto p3 = generate3d("uniform", 4000, 4);
  const auto sphere = generate3d("sphere", 20000, 5);
  const auto xy = [](const std::vector<Point2>& p) { return &p.data()->x; };
  const auto xyz = [](const std::vector<Point3>& p) { return &p.data()->x; };
  const std::int64_t n2 = std::int64_t(p2.size()), n3 = std::int64_t(p3.size());

  // A binary image and a density, shared read-only by every call.
  std::vector<std::uint8_t> image(std::size_t(96 * 128));
  std::vector<double> density(std::size_t(64 * 80));
  std::mt19937_64 r(9);
  for (auto& v : image) v = (r() % 50) == 0;
  for (std::size_t i = 0; i < density.size(); ++i) density[i] = 1.0 + double(i % 80) / 8.0;

  J.push_back({"edt 2d", [=](int k) {
                 GridView g{image.data(), ScalarType::U8, {96, 128}};
                 EdtOptions o = on_backend<EdtOptions>(1 + k % 2);
                 o.squared = true;
                 o.features = o.labels = true;
                 if (k % 3 == 1)
                   o.tuning = gg_test::tuning([](Tuning& t) { t.edt.linear_packing = true; });
                 const EdtResult e = distance_transform(g, SiteRule::NonZero, o);
                 return Arrays()
                     .add("sqdist", e.sqdist_int)
                     .add("features", e.features)
                     .add("labels", e.labels);
               }});
  J.push_back({"edt 3d by slices", [=](int k) {
                 GridView g{image.data(), ScalarType::U8, {12, 8, 128}};
                 EdtOptions o = on_backend<EdtOptions>(1 + k % 2);
                 o.distance = 64;
                 o.features = true;
                 o.slices = {11, 0, 5, 6};
                 if (k % 3 == 2)
                   o.tuning = gg_test::tuning([](Tuning& t) { t.edt.column_packing = true; });
                 const EdtResult e = distance_transform(g, SiteRule::Zero, o);
                 return Arrays().add("distance", e.distance64).add("features", e.features);
               }});
  J.push_back({"centroidal voronoi", [=](int k) {
                 GridView g{density.data(), ScalarType::F64, {64, 80}};
                 CvdOptions o = on_backend<CvdOptions>(1 + k % 2);
                 o.num_sites = 200;
                 o.max_iterations = 4;
                 const CvdResult c = centroidal_voronoi(g, o);
                 return Arrays().add("sites", c.sites).add("mass", c.mass);
               }});
  J.push_back({"delaunay2d", [=](int k) {
                 Delaunay2dOptions o = on_backend<Delaunay2dOptions>(1 + k % 2);
                 if (k % 3 == 1)
                   o.tuning = gg_test::tuning([](Tuning& t) { t.del2d = {0, 16, 3, 1 << 30}; });
                 const Triangulation2d t = delaunay2d(xy(p2), n2, o);
                 return Arrays().add("triangles", t.triangles).add("neighbors", t.neighbors);
               }});
  J.push_back({"delaunay2d digital", [=](int k) {
                 Delaunay2dOptions o = on_backend<Delaunay2dOptions>(1 + k % 2);
                 if (k % 2) o.method = Method::Digital;
                 const Triangulation2d t = delaunay2d(xy(p2), n2, o);
                 const std::vector<std::int32_t> tri(t.triangles.begin(), t.triangles.end());
                 return Arrays().add("triangle set", simplex_set<3>(tri));
               }});
  J.push_back({"dynamic delaunay2d", [=](int k) {
                 DynamicDelaunay2d d(xy(p2), n2 / 2, on_backend<Delaunay2dOptions>(1 + k % 2));
                 d.insert(xy(p2) + 2 * (n2 / 2), n2 - n2 / 2);
                 const Triangulation2d t = d.triangulation();
                 const std::vector<std::int32_t> tri(t.triangles.begin(), t.triangles.end());
                 return Arrays().add("triangle set", simplex_set<3>(tri));
               }});
  J.push_back({"voronoi2d", [=](int k) {
                 const Voronoi2d v =
                     voronoi2d(xy(p2), n2, on_backend<Delaunay2dOptions>(1 + k % 2));
                 return Arrays().add("vertices", v.vertices).add("ridges", v.ridge_points);
               }});
  // A square with a slit: constrained and refined.
  const std::vector<double> poly{0, 0, 4, 0, 4, 4, 0, 4, 1, 2, 3, 2.5, 2, 1, 2.2, 3.1};
  const std::vector<std::int32_t> seg{0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 6, 7};
  J.push_back({"cdt2d", [=](int k) {
                 std::vector<double> pts = poly;
                 for (std::int64_t i = 0; i < 2000; ++i)
                   pts.insert(pts.end(), {4 * p2[std::size_t(i)].x, 4 * p2[std::size_t(i)].y});
                 Cdt2dOptions o = on_backend<Cdt2dOptions>(1 + k % 2);
                 o.crossings = Cdt2dOptions::Crossings::Split;
                 const auto c = cdt2d(pts.data(), std::int64_t(pts.size() / 2), seg.data(),
                                      std::int64_t(seg.size() / 2), o);
                 return Arrays().add("triangles", c.triangles).add("segment_of", c.segment_of);
               }});
  J.push_back({"refine2d", [=](int k) {
                 Refine2dOptions o = on_backend<Refine2dOptions>(1 + k % 2);
                 o.min_angle = 28;
                 o.max_area = 0.01;
                 o.crossings = Cdt2dOptions::Crossings::Split;
                 const auto m = refine2d(poly.data(), std::int64_t(poly.size() / 2), seg.data(),
                                         std::int64_t(seg.size() / 2), o);
                 return Arrays().add("points", m.points).add("triangles", m.triangles);
               }});
  J.push_back({"hull3d", [=](int k) {
                 Hull3dOptions o = on_backend<Hull3dOptions>(1 + k % 2);
                 if (k % 3 == 1)
                   o.tuning = gg_test::tuning([](Tuning& t) { t.hull3d.first_facet_slots = 8; });
                 const ConvexHull3d h = convex_hull3d(sphere, o);
                 return Arrays().add("triangles", h.triangles).add("neighbors", h.neighbors);
               }});
  J.push_back({"delaunay3d", [=](int k) {
                 Delaunay3dOptions o = on_backend<Delaunay3dOptions>(1 + k % 2);
                 const Triangulation3d t = delaunay3d(xyz(p3), n3, o);
                 return Arrays().add("tetrahedra", t.tetrahedra).add("neighbors", t.neighbors);
               }});
  J.push_back({"delaunay3d repaired", [=](int k) {
                 Delaunay3dOptions o = on_backend<Delaunay3dOptions>(1 + k % 2);
                 if (k % 3 == 1)
                   o.tuning = gg_test::tuning([](Tuning& t) { t.del3d.max_flip_rounds = 1; });
                 if (k % 3 == 2) o.method = Method::Digital;
                 const Triangulation3d t = delaunay3d(xyz(p3), n3, o);
                 const std::vector<std::int32_t> tet(t.tetrahedra.begin(), t.tetrahedra.end());
                 return Arrays().add("tetrahedron set", simplex_set<4>(tet));
               }});
  J.push_back({"voronoi3d", [=](int k) {
                 const Voronoi3d v =
                     voronoi3d(xyz(p3), n3, on_backend<Delaunay3dOptions>(1 + k % 2));
                 return Arrays().add("vertices", v.vertices).add("ridges", v.ridge_points);
               }});
  J.push_back({"voronoi cells", [=](int k) {
                 const VoronoiCells c =
                     voronoi_cells(xyz(p3), n3, on_backend<VoronoiCellsOptions>(1 + k % 2));
                 return Arrays().add("volumes", c.volumes).add("neighbors", c.neighbors);
               }});
  J.push_back({"find_simplex2d", [=](int k) {
                 const Triangulation2d t = delaunay2d(xy(p2), n2, on_backend<Delaunay2dOptions>(1));
                 LocateOptions lo;  // (host threads on either executor)
                 lo.threads = 1 + k % 2;
                 std::vector<double> q;  // midpoints of consecutive points
                 for (std::int64_t i = 0; i + 1 < 5000; ++i)
                   q.insert(q.end(), {(p2[std::size_t(i)].x + p2[std::size_t(i + 1)].x) / 2,
                                      (p2[std::size_t(i)].y + p2[std::size_t(i + 1)].y) / 2});
                 const auto s =
                     find_simplex2d(xy(p2), n2, t.triangles.data(), t.neighbors.data(),
                                    t.num_triangles, q.data(), std::int64_t(q.size() / 2), lo);
                 return Arrays().add("simplices", s);
               }});
  return J;
}

}  // namespace

// Each job alone with the defaults, then every job at once on its own host thread, each with
// options other than the defaults (three variants: thread counts, knobs, methods), twice.
TEST(ConcurrentCalls, EveryCapabilityAtOnceWithItsOwnOptions) {
  const std::vector<Job> J = jobs();
  std::vector<Arrays> want;
  for (const Job& j : J) want.push_back(j.run(0));
  for (int round = 0; round < 2; ++round) {
    const int tasks = int(3 * J.size());
    const auto got = gg_test::on_host_threads(tasks, [&](int t) {
      return J[std::size_t(t) % J.size()].run(1 + t / int(J.size()) + round);
    });
    for (int t = 0; t < tasks; ++t)
      expect_same(J[std::size_t(t) % J.size()].name + " (variant " +
                      std::to_string(1 + t / int(J.size()) + round) + ")",
                  want[std::size_t(t) % J.size()], got[std::size_t(t)]);
  }
}
