// The 3D Voronoi diagram's options (Voronoi3dOptions, issue 48): the diagram into the caller's
// arrays from the host and the device entry (the CPU executor's "device" memory is host memory),
// the same arrays as the library's own, the counts set and the result's arrays left empty; an
// array too short refused before any is written; the thread count not changing a result.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "../common/into_arrays.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/voronoi3d.hpp"

using namespace gpugeom;

namespace {
using B = Voronoi3dBuffers;
using R = Voronoi3d;
const auto kOutputs =
    std::make_tuple(gg_test::output(&B::vertices, &R::vertices, "vertices"),
                    gg_test::output(&B::ridge_points, &R::ridge_points, "ridge_points"),
                    gg_test::output(&B::ridge_offsets, &R::ridge_offsets, "ridge_offsets"),
                    gg_test::output(&B::ridge_vertices, &R::ridge_vertices, "ridge_vertices"),
                    gg_test::output(&B::region_offsets, &R::region_offsets, "region_offsets"),
                    gg_test::output(&B::region_vertices, &R::region_vertices, "region_vertices"),
                    gg_test::output(&B::simplex_vertex, &R::simplex_vertex, "simplex_vertex"));
using Arrays = decltype(gg_test::IntoArrays(std::declval<const R&>(), kOutputs));

template <class V>
void expect_counts(const V& v, const R& ref) {
  EXPECT_EQ(v.num_points, ref.num_points);
  EXPECT_EQ(v.num_vertices, ref.num_vertices);
  EXPECT_EQ(v.num_ridges, ref.num_ridges);
  EXPECT_EQ(v.num_ridge_vertices, ref.num_ridge_vertices);
  EXPECT_EQ(v.num_region_vertices, ref.num_region_vertices);
}
}  // namespace

TEST(Voronoi3d, IntoCallerArrays) {
  for (const char* d : {"grid", "uniform"}) {  // (a grid's cospherical tetrahedra share vertices)
    SCOPED_TRACE(d);
    auto p = generate3d(d, 800, 7);
    for (int k = 0; k < 10; ++k) p.push_back(p[std::size_t(17 * k)]);  // duplicates
    const std::int64_t n = std::int64_t(p.size());
    const double* xyz = &p.data()->x;
    Delaunay3dOptions to;
    to.backend = Backend::Cpu;
    const auto tri = delaunay3d(xyz, n, to);
    const auto dt = delaunay3d_device(xyz, n, to);
    Voronoi3dOptions o;
    o.backend = Backend::Cpu;
    const R ref = voronoi3d(xyz, n, tri, o);
    // The counts describe the arrays.
    EXPECT_EQ(ref.num_points, n);
    EXPECT_EQ(3 * ref.num_vertices, std::int64_t(ref.vertices.size()));
    EXPECT_EQ(2 * ref.num_ridges, std::int64_t(ref.ridge_points.size()));
    EXPECT_EQ(ref.num_ridge_vertices, std::int64_t(ref.ridge_vertices.size()));
    EXPECT_EQ(ref.num_region_vertices, std::int64_t(ref.region_vertices.size()));
    EXPECT_EQ(ref.stats.voronoi_vertices, ref.num_vertices);
    EXPECT_EQ(ref.stats.voronoi_ridges, ref.num_ridges);
    EXPECT_EQ(ref.stats.backend, Backend::Cpu);
    for (const bool device : {false, true}) {
      SCOPED_TRACE(device ? "device entry" : "host entry");
      Arrays a(ref, kOutputs);
      o.into = a.buffers();
      if (device) {
        const DeviceVoronoi3d v = voronoi3d_device(xyz, n, dt, o);
        EXPECT_FALSE(v.vertices || v.ridge_points || v.ridge_offsets || v.ridge_vertices ||
                     v.region_offsets || v.region_vertices || v.simplex_vertex);
        expect_counts(v, ref);
      } else {
        const R v = voronoi3d(xyz, n, tri, o);
        a.expect_none(v);
        expect_counts(v, ref);
      }
      a.expect_equal(ref);
      // One array too short: refused, naming it and both lengths, nothing written.
      Arrays s(ref, kOutputs, "region_vertices");
      o.into = s.buffers();
      const std::string need =
          "into.region_vertices holds " + std::to_string(ref.num_region_vertices - 1) +
          " elements; this result needs at least " + std::to_string(ref.num_region_vertices);
      if (device)
        gg_test::expect_refused([&] { (void)voronoi3d_device(xyz, n, dt, o); }, need);
      else
        gg_test::expect_refused([&] { (void)voronoi3d(xyz, n, tri, o); }, need);
      EXPECT_TRUE(s.untouched());
    }
    // The thread count does not change the arrays.
    o.into = {};
    o.threads = 1;
    const R one = voronoi3d(xyz, n, tri, o);
    EXPECT_EQ(one.vertices, ref.vertices);
    EXPECT_EQ(one.ridge_vertices, ref.ridge_vertices);
    EXPECT_EQ(one.region_vertices, ref.region_vertices);
  }
}
