// The 3D Voronoi diagram's options (Voronoi3dOptions, issue 48): the diagram into the caller's
// arrays from the host and the device entry (the CPU executor's "device" memory is host memory),
// the same arrays as the library's own, the counts set and the result's arrays left empty; an
// array too short refused before any is written; the thread count not changing a result.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "../common/caller_arrays.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/voronoi3d.hpp"

using namespace gpugeom;
using gg_test::CallerArray;

namespace {

template <class T>
std::vector<T> vec(const HostVector<T>& h) {
  return std::vector<T>(h.begin(), h.end());
}

// The caller's arrays for a diagram of ref's size (region_vertices `short_by` shorter), filled
// with a value no result holds.
struct Arrays {
  CallerArray<double> vertices;
  CallerArray<std::int32_t> ridge_points, ridge_vertices, region_vertices, simplex_vertex;
  CallerArray<std::int64_t> ridge_offsets, region_offsets;
  Arrays(const Voronoi3d& ref, std::int64_t short_by)
      : vertices(3 * ref.num_vertices, -7.0),
        ridge_points(2 * ref.num_ridges, -7),
        ridge_vertices(ref.num_ridge_vertices, -7),
        region_vertices(ref.num_region_vertices - short_by, -7),
        simplex_vertex(std::int64_t(ref.simplex_vertex.size()), -7),
        ridge_offsets(ref.num_ridges + 1, -7),
        region_offsets(ref.num_points + 1, -7) {}
  Voronoi3dBuffers buffers() {
    Voronoi3dBuffers b;
    b.vertices = vertices.buf();
    b.ridge_points = ridge_points.buf();
    b.ridge_vertices = ridge_vertices.buf();
    b.region_vertices = region_vertices.buf();
    b.simplex_vertex = simplex_vertex.buf();
    b.ridge_offsets = ridge_offsets.buf();
    b.region_offsets = region_offsets.buf();
    return b;
  }
  bool untouched() const {
    return vertices.untouched(-7.0) && ridge_points.untouched(-7) && ridge_vertices.untouched(-7) &&
           region_vertices.untouched(-7) && simplex_vertex.untouched(-7) &&
           ridge_offsets.untouched(-7) && region_offsets.untouched(-7);
  }
  void expect_equal(const Voronoi3d& ref) const {
    EXPECT_EQ(vertices.v, vec(ref.vertices));
    EXPECT_EQ(ridge_points.v, vec(ref.ridge_points));
    EXPECT_EQ(ridge_vertices.v, vec(ref.ridge_vertices));
    EXPECT_EQ(region_vertices.v, vec(ref.region_vertices));
    EXPECT_EQ(simplex_vertex.v, vec(ref.simplex_vertex));
    EXPECT_EQ(ridge_offsets.v, vec(ref.ridge_offsets));
    EXPECT_EQ(region_offsets.v, vec(ref.region_offsets));
  }
};

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
    const Voronoi3d ref = voronoi3d(xyz, n, tri, o);
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
      Arrays a(ref, 0);
      o.into = a.buffers();
      if (device) {
        const DeviceVoronoi3d v = voronoi3d_device(xyz, n, dt, o);
        EXPECT_FALSE(v.vertices || v.ridge_points || v.ridge_offsets || v.ridge_vertices ||
                     v.region_offsets || v.region_vertices || v.simplex_vertex);
        EXPECT_EQ(v.num_vertices, ref.num_vertices);
        EXPECT_EQ(v.num_ridges, ref.num_ridges);
        EXPECT_EQ(v.num_ridge_vertices, ref.num_ridge_vertices);
        EXPECT_EQ(v.num_region_vertices, ref.num_region_vertices);
      } else {
        const Voronoi3d v = voronoi3d(xyz, n, tri, o);
        EXPECT_TRUE(v.vertices.empty() && v.ridge_points.empty() && v.ridge_offsets.empty() &&
                    v.ridge_vertices.empty() && v.region_offsets.empty() &&
                    v.region_vertices.empty() && v.simplex_vertex.empty());
        EXPECT_EQ(v.num_vertices, ref.num_vertices);
        EXPECT_EQ(v.num_ridges, ref.num_ridges);
        EXPECT_EQ(v.num_ridge_vertices, ref.num_ridge_vertices);
        EXPECT_EQ(v.num_region_vertices, ref.num_region_vertices);
      }
      a.expect_equal(ref);
      // One array too short: refused, naming it and both lengths, nothing written.
      Arrays s(ref, 1);
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
    const Voronoi3d one = voronoi3d(xyz, n, tri, o);
    EXPECT_EQ(one.vertices, ref.vertices);
    EXPECT_EQ(one.ridge_vertices, ref.ridge_vertices);
    EXPECT_EQ(one.region_vertices, ref.region_vertices);
  }
}
