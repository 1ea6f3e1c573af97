// The 2D Voronoi diagram's options (Voronoi2dOptions, issue 48): the diagram into the caller's
// arrays from the host and the device entry (the CPU executor's "device" memory is host memory),
// the same arrays as the library's own, the counts set and the result's arrays left empty; an
// array too short refused before any is written; the thread count not changing a result.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "../common/into_arrays.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/generate.hpp"

using namespace gpugeom;

namespace {
using B = Voronoi2dBuffers;
using R = Voronoi2d;
const auto kOutputs =
    std::make_tuple(gg_test::output(&B::vertices, &R::vertices, "vertices"),
                    gg_test::output(&B::ridge_points, &R::ridge_points, "ridge_points"),
                    gg_test::output(&B::ridge_vertices, &R::ridge_vertices, "ridge_vertices"),
                    gg_test::output(&B::ridge_directions, &R::ridge_directions, "ridge_directions"),
                    gg_test::output(&B::cell_offsets, &R::cell_offsets, "cell_offsets"),
                    gg_test::output(&B::cell_vertices, &R::cell_vertices, "cell_vertices"),
                    gg_test::output(&B::simplex_vertex, &R::simplex_vertex, "simplex_vertex"));
using Arrays = decltype(gg_test::IntoArrays(std::declval<const R&>(), kOutputs));

void expect_counts(const DeviceVoronoi2d& v, const R& ref) {
  EXPECT_EQ(v.num_vertices, ref.num_vertices);
  EXPECT_EQ(v.num_ridges, ref.num_ridges);
  EXPECT_EQ(v.num_cell_vertices, ref.num_cell_vertices);
}
void expect_counts(const R& v, const R& ref) {
  EXPECT_EQ(v.num_points, ref.num_points);
  EXPECT_EQ(v.num_vertices, ref.num_vertices);
  EXPECT_EQ(v.num_ridges, ref.num_ridges);
  EXPECT_EQ(v.num_cell_vertices, ref.num_cell_vertices);
}
}  // namespace

TEST(Voronoi2d, IntoCallerArrays) {
  for (const char* d : {"grid", "uniform"}) {  // (a grid's cocircular triangles share vertices)
    SCOPED_TRACE(d);
    auto p = generate2d(d, 1500, 7);
    for (int k = 0; k < 10; ++k) p.push_back(p[std::size_t(17 * k)]);  // duplicates
    const std::int64_t n = std::int64_t(p.size());
    const double* xy = &p.data()->x;
    Delaunay2dOptions to;
    to.backend = Backend::Cpu;
    const auto tri = delaunay2d(xy, n, to);
    const auto dt = delaunay2d_device(xy, n, to);
    Voronoi2dOptions o;
    o.backend = Backend::Cpu;
    const R ref = voronoi2d(xy, n, tri, o);
    // The counts describe the arrays.
    EXPECT_EQ(ref.num_points, n);
    EXPECT_EQ(2 * ref.num_vertices, std::int64_t(ref.vertices.size()));
    EXPECT_EQ(2 * ref.num_ridges, std::int64_t(ref.ridge_points.size()));
    EXPECT_EQ(ref.num_cell_vertices, std::int64_t(ref.cell_vertices.size()));
    EXPECT_EQ(ref.stats.backend, Backend::Cpu);
    ASSERT_FALSE(ref.stats.phase_ms.empty());
    EXPECT_EQ(ref.stats.phase_ms.back().first, "voronoi");
    for (const bool device : {false, true}) {
      SCOPED_TRACE(device ? "device entry" : "host entry");
      Arrays a(ref, kOutputs);
      o.into = a.buffers();
      if (device) {
        const DeviceVoronoi2d v = voronoi2d_device(xy, n, dt, o);
        EXPECT_FALSE(v.vertices || v.ridge_points || v.ridge_vertices || v.ridge_directions ||
                     v.cell_offsets || v.cell_vertices || v.simplex_vertex);
        expect_counts(v, ref);
      } else {
        const R v = voronoi2d(xy, n, tri, o);
        a.expect_none(v);
        expect_counts(v, ref);
      }
      a.expect_equal(ref);
      // One array too short: refused, naming it and both lengths, nothing written.
      Arrays s(ref, kOutputs, "cell_vertices");
      o.into = s.buffers();
      const std::string need =
          "into.cell_vertices holds " + std::to_string(ref.num_cell_vertices - 1) +
          " elements; this result needs at least " + std::to_string(ref.num_cell_vertices);
      if (device)
        gg_test::expect_refused([&] { (void)voronoi2d_device(xy, n, dt, o); }, need);
      else
        gg_test::expect_refused([&] { (void)voronoi2d(xy, n, tri, o); }, need);
      EXPECT_TRUE(s.untouched());
    }
    // Only some arrays given: those written, the rest in the result.
    gg_test::CallerArray<double> verts(2 * ref.num_vertices, -7.0);
    o.into = {};
    o.into.vertices = verts.buf();
    const R part = voronoi2d(xy, n, tri, o);
    EXPECT_EQ(verts.v, std::vector<double>(ref.vertices.begin(), ref.vertices.end()));
    EXPECT_TRUE(part.vertices.empty());
    EXPECT_EQ(part.cell_vertices, ref.cell_vertices);
    // The thread count does not change the arrays.
    o.into = {};
    o.threads = 1;
    const R one = voronoi2d(xy, n, tri, o);
    EXPECT_EQ(one.vertices, ref.vertices);
    EXPECT_EQ(one.ridge_vertices, ref.ridge_vertices);
    EXPECT_EQ(one.cell_vertices, ref.cell_vertices);
  }
}

// options_from carries one call's executor settings to another capability's options.
TEST(Voronoi2d, OptionsFromRunOptions) {
  Delaunay2dOptions d;
  d.backend = Backend::Cpu;
  d.threads = 3;
  d.device = 1;
  d.profile = true;
  d.method = Method::Digital;
  const auto v = options_from<Voronoi2dOptions>(d);
  EXPECT_EQ(v.backend, Backend::Cpu);
  EXPECT_EQ(v.threads, 3);
  EXPECT_EQ(v.device, 1);
  EXPECT_TRUE(v.profile);
  EXPECT_FALSE(v.into.vertices);
}
