// The CUDA executor's 3D Delaunay tetrahedralisation: valid by the exact checker on every
// distribution and degenerate input it takes, and the CPU executor's arrays entry for entry
// (the same tetrahedra in the same order with the same neighbours: slot numbers, records and
// list orders follow ranks in list order on both executors).
#include <cuda_runtime.h>

#include <algorithm>
#include <array>
#include <set>
#include <cstdlib>
#include <string>

#include "../common/capped_sizes.hpp"
#include "../common/tuning.hpp"
#include "../common/device_arrays.hpp"
#include "del3d_cases.hpp"

using namespace gpugeom;

namespace {
// Under compute-sanitizer the large cases take too long: GG_DEL3D_MAX_N caps the sizes.
std::vector<std::int64_t> sizes(std::vector<std::int64_t> s) {
  return gg_test::capped_sizes("GG_DEL3D_MAX_N", std::move(s));
}

void same_on_both(const gg_hull3d::Case& c, bool compare = true) {
  SCOPED_TRACE(c.name);
  Delaunay3dOptions o;
  o.backend = Backend::Cuda;
  const auto gpu = delaunay3d(c.pts, o);
  gg_del3d::expect_valid(c.pts, gpu);
  if (!compare) return;
  o.backend = Backend::Cpu;
  const auto cpu = delaunay3d(c.pts, o);
  EXPECT_EQ(gg_del3d::tet_set(gpu.tetrahedra), gg_del3d::tet_set(cpu.tetrahedra));
  gg_del3d::expect_same_arrays(cpu, gpu, c.name + ": CPU and CUDA");
}
}  // namespace

TEST(CudaDelaunay3d, Distributions) {
  for (const auto& c : gg_hull3d::distribution_cases(sizes({5, 100, 5000, 200000}), 17)) {
    if (c.name.rfind("two_lines", 0) == 0 && c.pts.size() > 100) continue;  // (quadratic)
    same_on_both(c, c.pts.size() <= 5000);
  }
}

TEST(CudaDelaunay3d, Degenerate) {
  for (const auto& c : gg_hull3d::degenerate_cases()) same_on_both(c);
}

// Phase 2 alone on the device: no flips after the insertions (a tetrahedralisation far from
// Delaunay) or one round; star splaying repairs it there, into the CPU executor's arrays.
TEST(CudaDelaunay3d, StarSplayingRepairs) {
  for (const std::int64_t rounds : {0, 1})
    for (const char* d : {"uniform", "sphere", "thin_sphere", "gaussian", "grid"}) {
      SCOPED_TRACE(std::string(d) + ", rounds " + std::to_string(rounds));
      const auto pts = gpugeom::generate3d(d, sizes({3000})[0], 5);
      Delaunay3dOptions o;
      o.backend = Backend::Cuda;
      o.tuning = gg_test::tuning([&](detail::Tuning& t) { t.del3d.max_flip_rounds = rounds; });
      const auto gpu = delaunay3d(pts, o);
      gg_del3d::expect_valid(pts, gpu);
      EXPECT_GT(gpu.stats.failed_vertices, 0);
      o.backend = Backend::Cpu;
      gg_del3d::expect_same_arrays(delaunay3d(pts, o), gpu, "CPU and CUDA");
    }
}

// A race would show as different arrays: run after run, the same bytes (phase 2 repairs stars
// on the thin sphere; both methods).
TEST(CudaDelaunay3d, Repeatable) {
  for (const Method method : {Method::Incremental, Method::Digital})
    for (const char* d : {"ball", "thin_sphere"}) {
      const auto pts = gpugeom::generate3d(d, sizes({100000, 5000}).front(), 3);
      Delaunay3dOptions o;
      o.backend = Backend::Cuda;
      o.method = method;
      const auto ref = delaunay3d(pts, o);
      for (int r = 0; r < 3; ++r)
        gg_del3d::expect_same_arrays(ref, delaunay3d(pts, o),
                                     std::string(d) + (r ? "" : " (first repeat)"));
    }
}

TEST(CudaDelaunay3d, DeviceResident) {  // points on the GPU in, result left there
  auto p = gpugeom::generate3d("ball", sizes({50000, 3000}).front(), 8);
  p.push_back(p[7]);  // a duplicate
  const auto r = [&] {
    const gg_test::DeviceCopy dp(p);
    return delaunay3d_device(dp.doubles(), std::int64_t(p.size()));
  }();
  Delaunay3dOptions o;
  o.backend = Backend::Cuda;
  const auto h = delaunay3d(p, o);
  ASSERT_EQ(r.num_tetrahedra, h.num_tetrahedra);
  EXPECT_EQ(r.num_duplicates, 1);
  const std::int64_t nt = r.num_tetrahedra;
  const std::int64_t np = std::int64_t(p.size());
  const auto tets = gg_test::from_device(r.tetrahedra, 4 * nt);
  const auto nbrs = gg_test::from_device(r.neighbors, 4 * nt);
  const auto dup = gg_test::from_device(r.duplicate_of, np);
  EXPECT_EQ(gg_del3d::tet_set(tets), gg_del3d::tet_set(h.tetrahedra));
  EXPECT_EQ(dup, h.duplicate_of);
  // The vertex map and the hull facets: every vertex's tetrahedron has it; the same hull.
  ASSERT_EQ(r.num_hull_facets, h.num_hull_facets);
  const auto v2s = gg_test::from_device(r.vertex_to_simplex, np);
  const auto hull = gg_test::from_device(r.hull_facets, 3 * r.num_hull_facets);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::int32_t c = v2s[i], v = dup[i] >= 0 ? dup[i] : std::int32_t(i);
    ASSERT_GE(c, 0);
    ASSERT_TRUE(tets[4 * c] == v || tets[4 * c + 1] == v || tets[4 * c + 2] == v ||
                tets[4 * c + 3] == v)
        << "point " << i;
  }
  auto facet_set = [](const auto& f) {
    std::set<std::array<std::int32_t, 3>> s;
    for (std::size_t i = 0; i + 2 < f.size(); i += 3) {
      std::array<std::int32_t, 3> a{f[i], f[i + 1], f[i + 2]};
      std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());  // keeps orientation
      s.insert(a);
    }
    return s;
  };
  EXPECT_EQ(facet_set(hull), facet_set(h.hull_facets));
  for (std::int64_t c = 0; c < nt; ++c)  // neighbours point back (slot order may differ)
    for (int k = 0; k < 4; ++k) {
      const std::int32_t q = nbrs[std::size_t(4 * c + k)];
      if (q < 0) continue;
      ASSERT_LT(q, nt);
      int back = 0;
      for (int j = 0; j < 4; ++j) back += nbrs[std::size_t(4 * q + j)] == c;
      ASSERT_EQ(back, 1) << "tetrahedron " << c << " face " << k;
    }
}

// DigiDel3D on the GPU: valid, the same tetrahedra as the incremental method on the GPU, and as
// the digital method on the CPU executor where that is quick.
namespace {
void digital_same(const gg_hull3d::Case& c, std::int64_t grid, bool with_cpu) {
  SCOPED_TRACE(c.name + ", grid " + std::to_string(grid));
  Delaunay3dOptions o;
  o.backend = Backend::Cuda;
  const auto inc = delaunay3d(c.pts, o);
  o.method = Method::Digital;
  o.grid = grid;
  const auto dig = delaunay3d(c.pts, o);
  gg_del3d::expect_valid(c.pts, dig);
  EXPECT_EQ(gg_del3d::tet_set(dig.tetrahedra), gg_del3d::tet_set(inc.tetrahedra));
  if (!with_cpu) return;
  o.backend = Backend::Cpu;
  const auto cpu = delaunay3d(c.pts, o);
  EXPECT_EQ(gg_del3d::tet_set(dig.tetrahedra), gg_del3d::tet_set(cpu.tetrahedra));
  gg_del3d::expect_same_arrays(cpu, dig, c.name + ": digital, CPU and CUDA");
  EXPECT_EQ(dig.stats.digital_splay_rounds, cpu.stats.digital_splay_rounds);
  EXPECT_EQ(dig.stats.digital_star_insertions, cpu.stats.digital_star_insertions);
}
}  // namespace

// DynamicDelaunay3d on the CUDA executor (issue 47): after every insertion the
// tetrahedralisation of a fresh call, and at the end the same arrays as the CPU executor's after
// the same calls.
TEST(CudaDynamicDelaunay3d, SameAsFreshAndAsCpu) {
  std::uint64_t seed = 200;
  auto both = [&](const gg_hull3d::Case& c) {
    SCOPED_TRACE(c.name);
    Delaunay3dOptions o;
    o.backend = Backend::Cuda;
    const auto gpu = gg_del3d::follow_in_chunks(c, o, seed);
    o.backend = Backend::Cpu;
    const auto cpu = gg_del3d::follow_in_chunks(c, o, seed);
    ++seed;
    gg_del3d::expect_same_arrays(gpu, cpu, "CUDA and CPU executors");
  };
  for (const auto& c : gg_hull3d::degenerate_cases()) both(c);
  for (const auto& c : gg_hull3d::distribution_cases(sizes({100, 5000, 100000}), 31)) {
    if (c.name.rfind("two_lines", 0) == 0 && c.pts.size() > 100) continue;
    both(c);
  }
}

// Points on the GPU in (from_device, insert_device), the state and the results left there.
TEST(CudaDynamicDelaunay3d, DeviceResident) {
  auto p = gpugeom::generate3d("uniform", sizes({200000, 3000}).front(), 12);
  const std::int64_t n = std::int64_t(p.size());
  p.push_back(p[3]);  // a duplicate of a point inserted first
  const gg_test::DeviceCopy dp(p);
  auto d = DynamicDelaunay3d::from_device(dp.doubles(), n / 2);
  ASSERT_EQ(d.backend(), Backend::Cuda);
  d.insert_device(dp.doubles() + 3 * (n / 2), n - n / 2 + 1);
  EXPECT_EQ(d.num_duplicates(), 1);
  const auto r = d.device_tetrahedralisation();
  ASSERT_EQ(r.backend, Backend::Cuda);
  const auto host = d.tetrahedralisation();
  gg_del3d::expect_valid(p, host);
  ASSERT_EQ(r.num_tetrahedra, host.num_tetrahedra);
  const auto tet = gg_test::from_device(r.tetrahedra, 4 * r.num_tetrahedra);
  const auto dup = gg_test::from_device(r.duplicate_of, n + 1);
  EXPECT_TRUE(std::equal(tet.begin(), tet.end(), host.tetrahedra.begin()));
  EXPECT_EQ(dup[std::size_t(n)], 3);
}

// The same sequence of calls gives the same arrays run after run (a race would not).
TEST(CudaDynamicDelaunay3d, Repeatable) {
  for (const char* d : {"uniform", "grid"}) {
    SCOPED_TRACE(d);
    const auto p = gpugeom::generate3d(d, sizes({200000, 5000}).front(), 13);
    const std::int64_t n = std::int64_t(p.size());
    auto run = [&] {
      Delaunay3dOptions o;
      o.backend = Backend::Cuda;
      DynamicDelaunay3d t(&p.data()->x, n - 1000, o);
      t.insert(&p[std::size_t(n - 1000)].x, 1000);
      return t.tetrahedralisation();
    };
    const auto a = run();
    for (int r = 0; r < 2; ++r) gg_del3d::expect_same_arrays(a, run(), "runs");
  }
}

TEST(CudaDigitalDelaunay3d, SameAsIncrementalOnDistributions) {
  for (const auto& c : gg_hull3d::distribution_cases(sizes({5, 100, 5000, 20000}), 17)) {
    if (c.name.rfind("two_lines", 0) == 0 && c.pts.size() > 100) continue;  // (quadratic)
    digital_same(c, 0, c.pts.size() <= 5000);
  }
}

TEST(CudaDigitalDelaunay3d, SameAsIncrementalOnDegenerateInput) {
  for (const auto& c : gg_hull3d::degenerate_cases()) digital_same(c, 0, true);
}

TEST(CudaDigitalDelaunay3d, SameOnCoarseAndFineGrids) {
  for (const char* d : {"uniform", "gaussian", "thin_sphere", "grid"}) {
    const gg_hull3d::Case c{std::string(d),
                            gpugeom::generate3d(d, sizes({20000, 3000}).front(), 11)};
    for (std::int64_t g : {16, 48, 256}) digital_same(c, g, false);
  }
}

// insert, move and remove in random sequences on the CUDA executor (issue 47): after every call
// the tetrahedralisation of a fresh call on the points left.
TEST(CudaDynamicDelaunay3d, RandomOperationsGiveTheFreshTetrahedralisation) {
  Delaunay3dOptions o;
  o.backend = Backend::Cuda;
  auto cases = gg_hull3d::degenerate_cases();
  for (const auto& c : gg_hull3d::distribution_cases(sizes({60, 3000, 50000}), 43))
    if (c.name.rfind("two_lines", 0) != 0) cases.push_back(c);
  gg_test::random_operations<gg_del3d::Kept3d>(cases, o, 700, 1, 8);
}

// A removal gives the CPU executor's arrays, and a fresh tetrahedralisation's of the points left.
TEST(CudaDynamicDelaunay3d, RemoveAsOnTheCpu) {
  const auto p = gpugeom::generate3d("uniform", sizes({200000, 5000}).front(), 14);
  const std::int64_t n = std::int64_t(p.size());
  std::vector<std::int32_t> gone;
  for (std::int32_t i = 3; i < n; i += 101) gone.push_back(i);
  auto run = [&](Backend b) {
    Delaunay3dOptions o;
    o.backend = b;
    DynamicDelaunay3d t(&p.data()->x, n, o);
    t.remove(gone.data(), std::int64_t(gone.size()));
    EXPECT_EQ(t.stats().remove_rebuilt, 0);
    return t.tetrahedralisation();
  };
  const auto a = run(Backend::Cuda);
  gg_del3d::expect_same_arrays(a, run(Backend::Cpu), "CUDA and CPU executors");
  std::vector<Point3> live;
  std::vector<std::int32_t> ids;
  for (std::int32_t i = 0; i < n; ++i)
    if ((i - 3) % 101 != 0 || i < 3) live.push_back(p[std::size_t(i)]), ids.push_back(i);
  const auto fresh = delaunay3d(live);
  std::vector<std::int32_t> mapped(fresh.tetrahedra.size());
  for (std::size_t e = 0; e < mapped.size(); ++e) mapped[e] = ids[std::size_t(fresh.tetrahedra[e])];
  EXPECT_EQ(gg_del3d::tet_set(a.tetrahedra), gg_del3d::tet_set(mapped));
}
