// The 3D Voronoi diagram on the GPU (issue 49): from a device tetrahedralisation, the host
// entry's arrays (CPU executor on the same tetrahedra) element for element, on general input,
// a grid (cospherical cubes) with a copy, and the degenerate cases.
#include <cuda_runtime.h>

#include <cmath>
#include <string>
#include <vector>

#include "../common/device_arrays.hpp"
#include "del3d_cases.hpp"
#include "gpugeom/voronoi3d.hpp"

using namespace gpugeom;

namespace {
template <class T>
std::vector<T> vec(const HostVector<T>& v) {
  return std::vector<T>(v.begin(), v.end());
}

void expect_as_on_the_host(const std::vector<Point3>& p) {
  const std::int64_t n = std::int64_t(p.size());
  const gg_test::DeviceCopy d_points(p);
  const double* dp = d_points.doubles();
  const auto dt = delaunay3d_device(dp, n);
  const auto v = voronoi3d_device(dp, n, dt);
  Delaunay3dOptions o;
  o.backend = Backend::Cuda;
  const auto h = delaunay3d(p, o);  // (the same tetrahedra, in the same order)
  Voronoi3dOptions cpu;
  cpu.backend = Backend::Cpu;
  const auto ref = voronoi3d(&p.data()->x, n, h, cpu);
  ASSERT_EQ(3 * v.num_vertices, std::int64_t(ref.vertices.size()));
  const auto x = gg_test::from_device(v.vertices, 3 * v.num_vertices);
  for (std::size_t k = 0; k < x.size(); ++k)  // (equal, or NaN on both)
    ASSERT_TRUE(x[k] == ref.vertices[k] || (x[k] != x[k] && ref.vertices[k] != ref.vertices[k]))
        << k;
  EXPECT_EQ(gg_test::from_device(v.ridge_points, 2 * v.num_ridges), vec(ref.ridge_points));
  EXPECT_EQ(gg_test::from_device(v.ridge_offsets, v.num_ridges + 1), vec(ref.ridge_offsets));
  EXPECT_EQ(gg_test::from_device(v.ridge_vertices, v.num_ridge_vertices), vec(ref.ridge_vertices));
  EXPECT_EQ(gg_test::from_device(v.region_offsets, n + 1), vec(ref.region_offsets));
  EXPECT_EQ(gg_test::from_device(v.region_vertices, v.num_region_vertices),
            vec(ref.region_vertices));
  EXPECT_EQ(gg_test::from_device(v.simplex_vertex, dt.num_tetrahedra), vec(ref.simplex_vertex));
  // host points, both structures made on the GPU in one call: the same arrays
  Triangulation3d t2;
  const auto both = voronoi3d(&p.data()->x, n, o, &t2);
  ASSERT_EQ(t2.num_tetrahedra, h.num_tetrahedra);
  EXPECT_EQ(
      vec(t2.tetrahedra),
      std::vector<std::int32_t>(h.tetrahedra.begin(), h.tetrahedra.begin() + 4 * h.num_tetrahedra));
  EXPECT_EQ(both.ridge_points, ref.ridge_points);
  EXPECT_EQ(both.ridge_vertices, ref.ridge_vertices);
  EXPECT_EQ(both.region_vertices, ref.region_vertices);
  EXPECT_EQ(both.simplex_vertex, ref.simplex_vertex);
  // The diagram of the host tetrahedralisation made on the GPU (Voronoi3dOptions, one upload):
  // the same arrays.
  Voronoi3dOptions gpu;
  gpu.backend = Backend::Cuda;
  const auto up = voronoi3d(&p.data()->x, n, h, gpu);
  EXPECT_EQ(up.stats.backend, Backend::Cuda);
  ASSERT_EQ(up.stats.phase_ms.size(), 2u);
  EXPECT_EQ(up.stats.phase_ms[0].first, "upload");
  EXPECT_EQ(up.num_ridges, ref.num_ridges);
  EXPECT_EQ(up.ridge_offsets, ref.ridge_offsets);
  EXPECT_EQ(up.ridge_vertices, ref.ridge_vertices);
  EXPECT_EQ(up.region_offsets, ref.region_offsets);
  EXPECT_EQ(up.region_vertices, ref.region_vertices);
  EXPECT_EQ(up.simplex_vertex, ref.simplex_vertex);
  // The device entry into the caller's device arrays: the same arrays, the library's left null.
  if (ref.num_ridge_vertices > 0 && dt.num_tetrahedra > 0) {
    const gg_test::DeviceCopy rv(
        std::vector<std::int32_t>(std::size_t(ref.num_ridge_vertices), -7));
    const gg_test::DeviceCopy sv(std::vector<std::int32_t>(std::size_t(dt.num_tetrahedra), -7));
    gpu.into.ridge_vertices = {static_cast<std::int32_t*>(rv.data()), ref.num_ridge_vertices};
    gpu.into.simplex_vertex = {static_cast<std::int32_t*>(sv.data()), dt.num_tetrahedra};
    const auto vi = voronoi3d_device(dp, n, dt, gpu);
    EXPECT_FALSE(vi.ridge_vertices || vi.simplex_vertex);
    EXPECT_TRUE(vi.ridge_points && vi.region_vertices);
    EXPECT_EQ(vi.num_ridge_vertices, ref.num_ridge_vertices);
    EXPECT_EQ(gg_test::back(static_cast<const std::int32_t*>(rv.data()), ref.num_ridge_vertices),
              vec(ref.ridge_vertices));
    EXPECT_EQ(gg_test::back(static_cast<const std::int32_t*>(sv.data()), dt.num_tetrahedra),
              vec(ref.simplex_vertex));
  }
}
}  // namespace

TEST(CudaVoronoi3d, AsOnTheHost) {
  expect_as_on_the_host(generate3d("uniform", 100000, 3));
  std::vector<Point3> grid;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 20; ++j)
      for (int k = 0; k < 10; ++k) grid.push_back({double(i), double(j), double(k)});
  grid.push_back(grid[123]);
  expect_as_on_the_host(grid);
  for (const auto& c : gg_hull3d::degenerate_cases()) {
    SCOPED_TRACE(c.name);
    try {
      expect_as_on_the_host(c.pts);
    } catch (const Error& e) {  // (the cases without a tetrahedralisation)
      EXPECT_EQ(e.code(), ErrorCode::DegenerateInput) << e.what();
    }
  }
}
