// 3D convex hull on the CPU executor: the checker on every distribution and degenerate input,
// errors, and CGAL's extreme points as an oracle where CGAL is installed.
#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <set>
#include <string>

#include "../common/caller_arrays.hpp"
#include "../common/tuning.hpp"
#include "../common/on_host_threads.hpp"
#include "hull3d_cases.hpp"

#ifdef GG_HAVE_CGAL
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>
#endif

using namespace gpugeom;
using gg_hull3d::expect_valid;

using gg_hull3d::cpu;

TEST(Hull3d, Distributions) {
  for (const auto& c : gg_hull3d::distribution_cases({4, 5, 10, 100, 1000, 20000}, 11)) {
    SCOPED_TRACE(c.name);
    expect_valid(c.pts, convex_hull3d(c.pts, cpu()));
  }
}

TEST(Hull3d, Degenerate) {
  for (const auto& c : gg_hull3d::degenerate_cases()) {
    SCOPED_TRACE(c.name);
    const auto h = convex_hull3d(c.pts, cpu());
    expect_valid(c.pts, h);
    if (c.name.rfind("grid", 0) == 0 || c.name == "cube_faces" || c.name == "box_copies")
      EXPECT_EQ(h.vertices.size(), 8u);  // the corners only
    if (c.name == "tetra_faces") EXPECT_EQ(h.vertices.size(), 4u);
    if (c.name == "octahedron_edges") EXPECT_EQ(h.vertices.size(), 6u);
    if (c.name == "cospherical") EXPECT_EQ(h.vertices.size(), c.pts.size());
  }
}

// The facet store grows with the hull (issue 23: the slots are no longer 2n up front). Forced to
// start at 8 slots it grows many times on every input, and the arrays are the same as with the
// default start. The store is the rounds' (the CPU executor's own schedule sizes its slots from
// the points), so the rounds run here, and their arrays are the CPU schedule's too.
TEST(Hull3d, GrowingFacetStoreGivesTheSameHull) {
  std::vector<gg_hull3d::Case> cases = gg_hull3d::degenerate_cases();
  for (auto& c : gg_hull3d::distribution_cases({100, 20000}, 5)) cases.push_back(std::move(c));
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const auto ref = convex_hull3d(c.pts, cpu());
    const auto r = convex_hull3d(c.pts, gg_test::tuned(cpu(), [](detail::Tuning& t) {
                                   t.hull3d.rounds = true;
                                   t.hull3d.first_facet_slots = 8;
                                 }));
    expect_valid(c.pts, r);
    EXPECT_EQ(r.triangles, ref.triangles);
    EXPECT_EQ(r.neighbors, ref.neighbors);
    EXPECT_EQ(r.vertices, ref.vertices);
    if (c.pts.size() > 100) EXPECT_GT(r.stats.facet_store_grown, 0);
  }
}

// The CPU executor's own schedule (points one by one by their cavities, the threads over chunks
// of the curve: hull3d/impl/one_by_one.inl) gives the rounds' arrays (the GPU's schedule, run
// here on the CPU executor), on every distribution and degenerate input, on 1, 2, 3 and 8
// threads: at 40 000 points the threads take chunks (and some points wait for the end); the
// small cases run on one thread alone whatever the count.
TEST(Hull3d, BothSchedulesGiveTheSameArrays) {
  std::vector<gg_hull3d::Case> cases = gg_hull3d::degenerate_cases();
  for (auto& c : gg_hull3d::distribution_cases({5, 1000, 40000}, 23)) cases.push_back(std::move(c));
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    Hull3dOptions o = gg_test::tuned(cpu(), [](detail::Tuning& t) { t.hull3d.rounds = true; });
    o.threads = 2;
    const auto ref = convex_hull3d(c.pts, o);
    EXPECT_EQ(ref.stats.cavity_insertions, 0);
    for (int t : {1, 2, 3, 8}) {
      Hull3dOptions one = cpu();
      one.threads = t;
      const auto r = convex_hull3d(c.pts, one);
      SCOPED_TRACE(std::to_string(t) + " threads");
      expect_valid(c.pts, r);
      EXPECT_EQ(r.triangles, ref.triangles);
      EXPECT_EQ(r.neighbors, ref.neighbors);
      EXPECT_EQ(r.vertices, ref.vertices);
      EXPECT_EQ(r.equations, ref.equations);
      EXPECT_EQ(r.stats.flips22 + r.stats.insert_rounds, 0);
      EXPECT_GE(r.stats.cavity_insertions, r.stats.first_pass_vertices - 4);
    }
  }
}

// The same arrays whatever the thread count (see Delaunay2d.SameForEveryThreadCount).
TEST(Hull3d, SameForEveryThreadCount) {
  for (const char* d : {"thin_sphere", "sphere", "grid"}) {
    const auto pts = generate3d(d, 20000, 4);
    Hull3dOptions o = cpu();
    o.threads = 1;
    const auto ref = convex_hull3d(pts, o);
    for (int t : {2, 3, 0}) {
      o.threads = t;
      const auto r = convex_hull3d(pts, o);
      EXPECT_EQ(r.triangles, ref.triangles) << d << ", " << t << " threads";
      EXPECT_EQ(r.neighbors, ref.neighbors) << d << ", " << t << " threads";
      EXPECT_EQ(r.vertices, ref.vertices) << d << ", " << t << " threads";
    }
  }
}

// The points go along a Hilbert curve and the perturbation follows it: the same point set in
// another order gives the same facets (as coordinates), flat faces included.
TEST(Hull3d, IndependentOfInputOrder) {
  for (const char* d : {"grid", "sphere", "thin_box"}) {
    const auto pts = generate3d(d, 3000, 9);
    std::vector<std::size_t> perm(pts.size());
    for (std::size_t i = 0; i < perm.size(); ++i) perm[i] = (i * 7919) % perm.size();
    std::vector<Point3> shuffled(pts.size());
    for (std::size_t i = 0; i < perm.size(); ++i) shuffled[i] = pts[perm[i]];
    using Tri = std::array<std::array<double, 3>, 3>;
    auto facets = [](const std::vector<Point3>& p, const ConvexHull3d& h) {
      std::set<Tri> out;
      for (std::size_t f = 0; f < h.num_facets; ++f) {
        Tri t;
        for (int k = 0; k < 3; ++k) {
          const Point3& q = p[std::size_t(h.triangles[3 * f + k])];
          t[std::size_t(k)] = {q.x, q.y, q.z};
        }
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // orientation kept
        out.insert(t);
      }
      return out;
    };
    const auto a = convex_hull3d(pts, cpu()), b = convex_hull3d(shuffled, cpu());
    EXPECT_EQ(facets(pts, a), facets(shuffled, b)) << d;
  }
}

// The perturbation depends on the points alone (src/predicates/sos.hpp): a prism over the 108
// integer points of a circle has two 108-gon faces, which the perturbation triangulates. A point
// added far below (and aside) changes the box and the curve order of every point, yet the top
// face keeps its triangles.
TEST(Hull3d, PerturbationDependsOnThePointsAlone) {
  std::vector<Point3> pts;
  const long r2 = 5L * 5 * 13 * 13 * 17 * 17;
  for (int z : {0, 1})
    for (long x = -1105; x <= 1105; ++x) {
      const long y2 = r2 - x * x;
      const long y = std::lround(std::sqrt(double(y2)));
      if (y * y != y2) continue;
      pts.push_back({double(x), double(y), double(z)});
      if (y) pts.push_back({double(x), double(-y), double(z)});
    }
  auto more = pts;
  more.push_back({-3e6, 2e6, -1e6});
  const auto a = convex_hull3d(pts, cpu()), b = convex_hull3d(more, cpu());
  auto key = [](const std::int32_t* v) {
    std::array<std::int32_t, 3> k{v[0], v[1], v[2]};
    std::rotate(k.begin(), std::min_element(k.begin(), k.end()), k.end());
    return k;
  };
  std::set<std::array<std::int32_t, 3>> in_b;
  for (std::size_t f = 0; f < b.num_facets; ++f) in_b.insert(key(&b.triangles[3 * f]));
  std::size_t checked = 0, kept = 0;
  for (std::size_t f = 0; f < a.num_facets; ++f) {
    bool top = true;
    for (int k = 0; k < 3; ++k) top = top && pts[std::size_t(a.triangles[3 * f + k])].z == 1;
    if (!top) continue;
    ++checked;
    kept += in_b.count(key(&a.triangles[3 * f]));
  }
  EXPECT_EQ(checked, pts.size() / 2 - 2);  // a triangulated 108-gon
  EXPECT_EQ(kept, checked);
}

// Of several copies of an extreme point, the first in input order is the vertex.
TEST(Hull3d, FirstCopyIsTheVertex) {
  std::vector<Point3> p = {{0.2, 0.2, 0.2}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0},
                           {1, 0, 0},       {0, 0, 0}, {0, 0, 1}, {0, 1, 0}, {0, 0, 0}};
  const auto h = convex_hull3d(p, cpu());
  EXPECT_EQ(h.vertices, (std::vector<std::int32_t>{1, 2, 3, 4}));
  EXPECT_EQ(h.stats.duplicates, 5);
  expect_valid(p, h);
}

// The counters are fields; counter_map() (the CLI's, the benches' and Python's) names each by
// its field's name, with its value. A cube with points inside its faces: the first pass may make
// them vertices, the extreme test drops them.
TEST(Hull3d, StatsAreNamedFields) {
  std::vector<Point3> p;
  for (int i = 0; i < 8; ++i) p.push_back({double(i & 1), double(i >> 1 & 1), double(i >> 2 & 1)});
  for (int d = 0; d < 3; ++d)
    for (double s : {0.0, 1.0}) {
      Point3 c{0.5, 0.5, 0.5};
      (d == 0 ? c.x : d == 1 ? c.y : c.z) = s;
      p.push_back(c);
    }
  p.push_back({0.5, 0.5, 0.5});
  p.push_back(p[3]);
  const auto h = convex_hull3d(p, cpu());
  expect_valid(p, h);
  const Hull3dStats& s = h.stats;
  EXPECT_EQ(h.num_vertices, 8);
  EXPECT_EQ(s.duplicates, 1);
  EXPECT_EQ(s.first_pass_vertices - s.nonextreme_vertices_dropped, 8);
  EXPECT_EQ(s.passes, s.nonextreme_vertices_dropped ? 2 : 1);
  EXPECT_GT(s.cavity_insertions, 0);  // (the CPU executor's own schedule)
  EXPECT_EQ(s.device_peak_bytes, 0);  // (the CPU executor)
  const std::pair<const char*, std::int64_t Hull3dStats::*> fields[] = {
      {"duplicates", &Hull3dStats::duplicates},
      {"passes", &Hull3dStats::passes},
      {"insert_rounds", &Hull3dStats::insert_rounds},
      {"facet_store_grown", &Hull3dStats::facet_store_grown},
      {"flip_rounds", &Hull3dStats::flip_rounds},
      {"flips22", &Hull3dStats::flips22},
      {"flips31", &Hull3dStats::flips31},
      {"labelled_nonextreme", &Hull3dStats::labelled_nonextreme},
      {"exact_predicates", &Hull3dStats::exact_predicates},
      {"first_pass_vertices", &Hull3dStats::first_pass_vertices},
      {"nonextreme_vertices_dropped", &Hull3dStats::nonextreme_vertices_dropped},
      {"digital_grid", &Hull3dStats::digital_grid},
      {"digital_render", &Hull3dStats::digital_render},
      {"sketch_points", &Hull3dStats::sketch_points},
      {"sketch_facets", &Hull3dStats::sketch_facets},
      {"depth_kept", &Hull3dStats::depth_kept},
      {"hull_input", &Hull3dStats::hull_input},
      {"digital_fallback", &Hull3dStats::digital_fallback},
      {"hull_candidates", &Hull3dStats::hull_candidates},
      {"outside_points", &Hull3dStats::outside_points},
      {"removed_vertices", &Hull3dStats::removed_vertices},
      {"cavity_insertions", &Hull3dStats::cavity_insertions},
      {"deferred_points", &Hull3dStats::deferred_points}};
  const auto m = s.counter_map();
  EXPECT_EQ(m.size(), std::size(fields));
  for (const auto& [name, field] : fields) {
    ASSERT_TRUE(m.count(name)) << name;
    EXPECT_EQ(m.at(name), s.*field) << name;
  }
  // A peak is printed where there is one.
  Hull3dStats peak = s;
  peak.device_peak_bytes = 4096;
  EXPECT_EQ(peak.counter_map().at("device_peak_bytes"), 4096);
  EXPECT_EQ(RunStats().counter_map(), (std::map<std::string, std::int64_t>{}));
}

TEST(Hull3d, ConcurrentCallsFromHostThreads) {
  const auto pts = generate3d("ball", 40000, 5);
  gg_test::expect_concurrent_calls_agree(
      [&](int threads) {
        Hull3dOptions o = cpu();
        o.threads = threads;
        return convex_hull3d(pts, o);
      },
      [](const ConvexHull3d& ref, const ConvexHull3d& got) {
        EXPECT_EQ(got.triangles, ref.triangles);
        EXPECT_EQ(got.neighbors, ref.neighbors);
      });
}

TEST(Hull3d, Errors) {
  auto code = [](const std::vector<Point3>& p) {
    try {
      convex_hull3d(p, cpu());
    } catch (const Error& e) {
      EXPECT_FALSE(std::string(e.what()).empty());
      return e.code();
    }
    return ErrorCode::Cuda;  // "no error": no test expects this code
  };
  const double nan = std::nan(""), inf = HUGE_VAL;
  EXPECT_EQ(code({}), ErrorCode::DegenerateInput);
  EXPECT_EQ(code({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), ErrorCode::DegenerateInput);
  // The count is refused before the points are read (int32 indices and the kernel point's);
  // 2^31 - 2 points are accepted (issue 23: the old limit was 2^28 - 8).
  try {
    const double one[3] = {0, 0, 0};
    convex_hull3d(one, std::int64_t(1) << 31, cpu());
    ADD_FAILURE() << "2^31 points accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidInput);
    EXPECT_NE(std::string(e.what()).find("at most 2147483646"), std::string::npos) << e.what();
  }
  EXPECT_EQ(code({{1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {1, 2, 3}}), ErrorCode::DegenerateInput);
  EXPECT_EQ(code({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {1, 1, 1}}),
            ErrorCode::DegenerateInput);
  EXPECT_EQ(code({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}}),
            ErrorCode::DegenerateInput);  // 3 distinct points
  EXPECT_EQ(code({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, nan}}), ErrorCode::InvalidInput);
  EXPECT_EQ(code({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {inf, 0, 1}}), ErrorCode::InvalidInput);
  EXPECT_EQ(code({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1e300}}), ErrorCode::InvalidInput);
  auto message = [](const std::vector<Point3>& p) {
    try {
      convex_hull3d(p, cpu());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({{0, 0, 0}, {1, 2, 3}, {2, 4, 6}, {0.5, 1, 1.5}}).find("one line"),
            std::string::npos);
  std::vector<Point3> plane;
  for (int i = 0; i < 100; ++i)
    plane.push_back({double(i % 10), double(i / 10), 2.0 * (i % 10) - 3.0 * (i / 10)});
  EXPECT_NE(message(plane).find("one plane"), std::string::npos);
  EXPECT_NE(message({{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}}).find("coincide"),
            std::string::npos);
  // nearly coplanar is not coplanar: exactly decided
  const auto h =
      convex_hull3d(std::vector<Point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1e-30}}, cpu());
  EXPECT_EQ(h.vertices.size(), 4u);
}

#ifdef GG_HAVE_CGAL
TEST(Hull3d, EqualsCgal) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  for (const char* d : {"ball", "gaussian", "thin_sphere", "sphere"})
    for (std::int64_t n : {1000, 100000}) {
      SCOPED_TRACE(std::string(d) + "/" + std::to_string(n));
      const auto pts = generate3d(d, n, 21);
      std::vector<K::Point_3> cp;
      for (const auto& p : pts) cp.emplace_back(p.x, p.y, p.z);
      CGAL::Surface_mesh<K::Point_3> sm;
      CGAL::convex_hull_3(cp.begin(), cp.end(), sm);
      std::set<std::array<double, 3>> want, got;
      for (auto v : sm.vertices()) {
        const auto& q = sm.point(v);
        want.insert({q.x(), q.y(), q.z()});
      }
      const auto h = convex_hull3d(pts, cpu());
      for (auto v : h.vertices) got.insert({pts[v].x, pts[v].y, pts[v].z});
      EXPECT_EQ(got, want);
    }
}
#endif

// The device entry on the CPU executor (its "device" memory is host memory) gives the host
// entry's result, planes included; the caller's arrays take the outputs on both entries; arrays
// too short for the result are refused before anything is written.
TEST(Hull3d, DeviceEntryAndCallerArrays) {
  using gg_test::CallerArray;
  using gg_test::host_prefix;
  for (const char* d : {"ball", "sphere", "grid"}) {
    SCOPED_TRACE(d);
    auto p = generate3d(d, 4000, 6);
    for (int k = 0; k < 30; ++k) p.push_back(p[std::size_t(31 * k)]);  // copies
    const std::int64_t n = std::int64_t(p.size());
    const double* xyz = &p.data()->x;
    const auto ref = convex_hull3d(p, cpu());
    const std::int64_t nf = ref.num_facets, nv = ref.num_vertices;
    ASSERT_EQ(ref.triangles.size(), std::size_t(3 * nf));
    ASSERT_EQ(ref.vertices.size(), std::size_t(nv));
    ASSERT_LE(nf, convex_hull3d_max_facets(n));

    const auto dv = convex_hull3d_device(xyz, n, cpu());
    EXPECT_EQ(dv.backend, Backend::Cpu);
    ASSERT_EQ(dv.num_facets, nf);
    ASSERT_EQ(dv.num_vertices, nv);
    EXPECT_EQ(host_prefix(dv.triangles, 3 * nf), ref.triangles);
    EXPECT_EQ(host_prefix(dv.neighbors, 3 * nf), ref.neighbors);
    EXPECT_EQ(host_prefix(dv.vertices, nv), ref.vertices);
    EXPECT_EQ(host_prefix(dv.equations, 4 * nf), ref.equations);

    const std::int64_t cap = convex_hull3d_max_facets(n);
    for (bool device : {false, true}) {
      SCOPED_TRACE(device ? "device entry" : "host entry");
      CallerArray<std::int32_t> t(3 * cap, 7), nb(3 * cap, 7), vx(n, 7);
      CallerArray<double> eq(4 * cap, 7);
      auto o = cpu();
      o.into = {t.buf(), nb.buf(), vx.buf(), eq.buf()};
      std::int64_t f = 0, v = 0;
      if (device) {
        const auto r = convex_hull3d_device(xyz, n, o);
        EXPECT_FALSE(r.triangles || r.neighbors || r.vertices || r.equations);
        f = r.num_facets, v = r.num_vertices;
      } else {
        const auto r = convex_hull3d(xyz, n, o);
        EXPECT_TRUE(r.triangles.empty() && r.vertices.empty() && r.equations.empty());
        f = r.num_facets, v = r.num_vertices;
      }
      ASSERT_EQ(f, nf);
      ASSERT_EQ(v, nv);
      EXPECT_EQ(host_prefix(t.v.data(), 3 * nf), ref.triangles);
      EXPECT_EQ(host_prefix(nb.v.data(), 3 * nf), ref.neighbors);
      EXPECT_EQ(host_prefix(vx.v.data(), nv), ref.vertices);
      EXPECT_EQ(host_prefix(eq.v.data(), 4 * nf), ref.equations);
      CallerArray<std::int32_t> t2(3 * cap, 7), v2(nv - 1, 7);
      o.into = {t2.buf(), {}, v2.buf(), {}};
      gg_test::expect_refused(
          [&] { device ? (void)convex_hull3d_device(xyz, n, o) : (void)convex_hull3d(xyz, n, o); },
          "into.vertices holds " + std::to_string(nv - 1));
      EXPECT_TRUE(t2.untouched(7) && v2.untouched(7));
    }
  }
}
