// The 2D Voronoi diagram's options (Voronoi2dOptions, issue 48): the diagram into the caller's
// arrays from the host and the device entry (the CPU executor's "device" memory is host memory),
// the same arrays as the library's own, the counts set and the result's arrays left empty; an
// array too short refused before any is written; the thread count not changing a result.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "../common/caller_arrays.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/generate.hpp"

using namespace gpugeom;
using gg_test::CallerArray;

namespace {

template <class T>
std::vector<T> vec(const HostVector<T>& h) {
  return std::vector<T>(h.begin(), h.end());
}

// The caller's arrays for a diagram of ref's size (cell_vertices `short_by` shorter), filled
// with a value no result holds.
struct Arrays {
  CallerArray<double> vertices, ridge_directions;
  CallerArray<std::int32_t> ridge_points, ridge_vertices, cell_vertices, simplex_vertex;
  CallerArray<std::int64_t> cell_offsets;
  Arrays(const Voronoi2d& ref, std::int64_t short_by)
      : vertices(2 * ref.num_vertices, -7.0),
        ridge_directions(2 * ref.num_ridges, -7.0),
        ridge_points(2 * ref.num_ridges, -7),
        ridge_vertices(2 * ref.num_ridges, -7),
        cell_vertices(ref.num_cell_vertices - short_by, -7),
        simplex_vertex(std::int64_t(ref.simplex_vertex.size()), -7),
        cell_offsets(ref.num_points + 1, -7) {}
  Voronoi2dBuffers buffers() {
    Voronoi2dBuffers b;
    b.vertices = vertices.buf();
    b.ridge_directions = ridge_directions.buf();
    b.ridge_points = ridge_points.buf();
    b.ridge_vertices = ridge_vertices.buf();
    b.cell_vertices = cell_vertices.buf();
    b.simplex_vertex = simplex_vertex.buf();
    b.cell_offsets = cell_offsets.buf();
    return b;
  }
  bool untouched() const {
    return vertices.untouched(-7.0) && ridge_directions.untouched(-7.0) &&
           ridge_points.untouched(-7) && ridge_vertices.untouched(-7) &&
           cell_vertices.untouched(-7) && simplex_vertex.untouched(-7) &&
           cell_offsets.untouched(-7);
  }
  void expect_equal(const Voronoi2d& ref) const {
    EXPECT_EQ(vertices.v, vec(ref.vertices));
    EXPECT_EQ(ridge_directions.v, vec(ref.ridge_directions));
    EXPECT_EQ(ridge_points.v, vec(ref.ridge_points));
    EXPECT_EQ(ridge_vertices.v, vec(ref.ridge_vertices));
    EXPECT_EQ(cell_vertices.v, vec(ref.cell_vertices));
    EXPECT_EQ(simplex_vertex.v, vec(ref.simplex_vertex));
    EXPECT_EQ(cell_offsets.v, vec(ref.cell_offsets));
  }
};

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
    const Voronoi2d ref = voronoi2d(xy, n, tri, o);
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
      Arrays a(ref, 0);
      o.into = a.buffers();
      if (device) {
        const DeviceVoronoi2d v = voronoi2d_device(xy, n, dt, o);
        EXPECT_FALSE(v.vertices || v.ridge_points || v.ridge_vertices || v.ridge_directions ||
                     v.cell_offsets || v.cell_vertices || v.simplex_vertex);
        EXPECT_EQ(v.num_vertices, ref.num_vertices);
        EXPECT_EQ(v.num_ridges, ref.num_ridges);
        EXPECT_EQ(v.num_cell_vertices, ref.num_cell_vertices);
      } else {
        const Voronoi2d v = voronoi2d(xy, n, tri, o);
        EXPECT_TRUE(v.vertices.empty() && v.ridge_points.empty() && v.ridge_vertices.empty() &&
                    v.ridge_directions.empty() && v.cell_offsets.empty() &&
                    v.cell_vertices.empty() && v.simplex_vertex.empty());
        EXPECT_EQ(v.num_vertices, ref.num_vertices);
        EXPECT_EQ(v.num_ridges, ref.num_ridges);
        EXPECT_EQ(v.num_cell_vertices, ref.num_cell_vertices);
      }
      a.expect_equal(ref);
      // One array too short: refused, naming it and both lengths, nothing written.
      Arrays s(ref, 1);
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
    CallerArray<double> verts(2 * ref.num_vertices, -7.0);
    o.into = {};
    o.into.vertices = verts.buf();
    const Voronoi2d part = voronoi2d(xy, n, tri, o);
    EXPECT_EQ(verts.v, vec(ref.vertices));
    EXPECT_TRUE(part.vertices.empty());
    EXPECT_EQ(part.cell_vertices, ref.cell_vertices);
    // The thread count does not change the arrays.
    o.into = {};
    o.threads = 1;
    const Voronoi2d one = voronoi2d(xy, n, tri, o);
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
