// Voronoi cells on the GPU (issue 49): the CPU executor's arrays bit for bit, from host points
// and from device points, bounded and periodic, on uniform and clustered input, a lattice, and a
// cell too large for a thread's room.
#include <cuda_runtime.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "../common/device_arrays.hpp"
#include "gpugeom/voronoi_cells.hpp"

using namespace gpugeom;

namespace {
template <class T>
std::vector<T> vec(const HostVector<T>& v) {
  return std::vector<T>(v.begin(), v.end());
}

void expect_as_on_the_host(const std::vector<double>& p, VoronoiCellsOptions o) {
  const std::int64_t n = std::int64_t(p.size() / 3);
  o.backend = Backend::Cpu;
  const VoronoiCells ref = voronoi_cells(p.data(), n, o);
  o.backend = Backend::Cuda;
  const VoronoiCells c = voronoi_cells(p.data(), n, o);
  EXPECT_EQ(vec(c.volumes), vec(ref.volumes));
  EXPECT_EQ(vec(c.areas), vec(ref.areas));
  EXPECT_EQ(vec(c.centroids), vec(ref.centroids));
  EXPECT_EQ(vec(c.face_offsets), vec(ref.face_offsets));
  EXPECT_EQ(vec(c.neighbors), vec(ref.neighbors));
  EXPECT_EQ(vec(c.face_areas), vec(ref.face_areas));
  EXPECT_EQ(vec(c.face_normals), vec(ref.face_normals));
  EXPECT_EQ(vec(c.face_vertex_offsets), vec(ref.face_vertex_offsets));
  EXPECT_EQ(vec(c.face_vertices), vec(ref.face_vertices));
  EXPECT_EQ(vec(c.vertex_offsets), vec(ref.vertex_offsets));
  EXPECT_EQ(vec(c.vertices), vec(ref.vertices));
  // device points in, device arrays out: the same
  const gg_test::DeviceCopy d(p);
  const DeviceVoronoiCells dc = voronoi_cells_device(d.doubles(), n, o);
  ASSERT_EQ(dc.num_faces, std::int64_t(ref.neighbors.size()));
  EXPECT_EQ(gg_test::from_device(dc.volumes, n), vec(ref.volumes));
  EXPECT_EQ(gg_test::from_device(dc.neighbors, dc.num_faces), vec(ref.neighbors));
  EXPECT_EQ(gg_test::from_device(dc.face_vertices, dc.num_face_vertices), vec(ref.face_vertices));
  EXPECT_EQ(gg_test::from_device(dc.vertices, 3 * dc.num_vertices), vec(ref.vertices));
  o.polygons = false;
  const DeviceVoronoiCells np = voronoi_cells_device(d.doubles(), n, o);
  EXPECT_EQ(gg_test::from_device(np.volumes, n), vec(ref.volumes));
  EXPECT_EQ(gg_test::from_device(np.face_areas, np.num_faces), vec(ref.face_areas));
  EXPECT_FALSE(np.vertices || np.face_vertices || np.face_vertex_offsets);
}

VoronoiCellsOptions box(bool px, bool py, bool pz) {
  VoronoiCellsOptions o;
  o.periodic[0] = px, o.periodic[1] = py, o.periodic[2] = pz;
  return o;
}
}  // namespace

TEST(CudaVoronoiCells, AsOnTheHost) {
  // GG_CELLS_N: fewer points (e.g. under compute-sanitizer)
  const char* env = std::getenv("GG_CELLS_N");
  const std::size_t n = env ? std::size_t(std::atol(env)) : 50000;
  std::mt19937_64 g(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> p(3 * n);
  for (double& x : p) x = u(g);
  expect_as_on_the_host(p, box(false, false, false));
  expect_as_on_the_host(p, box(true, true, true));
  expect_as_on_the_host(p, box(true, false, true));
  // clustered: Gaussian blobs, taken into the box
  std::normal_distribution<double> nd(0, 0.02);
  std::vector<double> c;
  for (std::size_t b = 0; b < n / 1000; ++b) {
    const double cx = u(g), cy = u(g), cz = u(g);
    for (int k = 0; k < 400; ++k)
      for (double x : {cx + nd(g), cy + nd(g), cz + nd(g)}) c.push_back(x - std::floor(x));
  }
  expect_as_on_the_host(c, box(true, true, true));
  // a lattice (cospherical everywhere) and a point inside a sphere of 400 (a cell of 400 faces)
  std::vector<double> l;
  for (int z = 0; z < 12; ++z)
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 12; ++x)
        for (int k : {x, y, z}) l.push_back((k + 0.5) / 12);
  expect_as_on_the_host(l, box(false, false, false));
  expect_as_on_the_host(l, box(true, true, true));
  std::vector<double> s = {0.5, 0.5, 0.5};
  for (int k = 0; k < 400; ++k) {
    const double zc = 1 - 2 * (k + 0.5) / 400, r = std::sqrt(1 - zc * zc), a = 2.399963 * k;
    for (double x : {0.5 + 0.3 * r * std::cos(a), 0.5 + 0.3 * r * std::sin(a), 0.5 + 0.3 * zc})
      s.push_back(x);
  }
  expect_as_on_the_host(s, box(false, false, false));
}

// The caller's device arrays (VoronoiCellsOptions::into) from the device entry, host arrays from
// the host entry on the GPU: the same values as the library's own.
TEST(CudaVoronoiCells, IntoCallersArrays) {
  const std::int64_t n = 5000;
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> p(std::size_t(3 * n));
  for (double& x : p) x = u(g);
  VoronoiCellsOptions o = box(true, true, false);
  o.backend = Backend::Cuda;
  const VoronoiCells ref = voronoi_cells(p.data(), n, o);
  const std::int64_t nf = ref.num_faces, ne = ref.num_face_vertices;
  std::vector<double> hv(static_cast<std::size_t>(n));
  std::vector<std::int32_t> hf(static_cast<std::size_t>(ne));
  VoronoiCellsOptions h = o;
  h.into.volumes = {hv.data(), n};
  h.into.face_vertices = {hf.data(), ne};
  const VoronoiCells hc = voronoi_cells(p.data(), n, h);
  EXPECT_TRUE(hc.volumes.empty() && hc.face_vertices.empty());
  EXPECT_EQ(hv, vec(ref.volumes));
  EXPECT_EQ(hf, vec(ref.face_vertices));
  EXPECT_EQ(vec(hc.neighbors), vec(ref.neighbors));

  const gg_test::DeviceCopy d(p);
  const gg_test::DeviceCopy dv(std::vector<double>(std::size_t(n), 7));
  const gg_test::DeviceCopy dn(std::vector<std::int32_t>(std::size_t(nf + 4), 7));
  VoronoiCellsOptions dev = o;
  dev.into.volumes = {static_cast<double*>(dv.data()), n};
  dev.into.neighbors = {static_cast<std::int32_t*>(dn.data()), nf + 4};
  const DeviceVoronoiCells dc = voronoi_cells_device(d.doubles(), n, dev);
  EXPECT_FALSE(dc.volumes || dc.neighbors);
  ASSERT_TRUE(dc.areas && dc.face_vertices);
  ASSERT_EQ(dc.num_faces, nf);
  std::vector<double> v(static_cast<std::size_t>(n));
  std::vector<std::int32_t> nb(std::size_t(nf + 4));
  ASSERT_EQ(cudaMemcpy(v.data(), dv.data(), v.size() * 8, cudaMemcpyDeviceToHost), cudaSuccess);
  ASSERT_EQ(cudaMemcpy(nb.data(), dn.data(), nb.size() * 4, cudaMemcpyDeviceToHost), cudaSuccess);
  EXPECT_EQ(v, vec(ref.volumes));
  EXPECT_EQ(std::vector<std::int32_t>(nb.begin(), nb.begin() + nf), vec(ref.neighbors));
  EXPECT_EQ(nb[std::size_t(nf)], 7);
  EXPECT_EQ(gg_test::from_device(dc.face_vertices, ne), vec(ref.face_vertices));
}
