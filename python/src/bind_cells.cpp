// gpugeom._core: Voronoi cells in a box (issue 49), for gpugeom.VoronoiCells (cells.py).
#include <nanobind/stl/array.h>
#include <nanobind/stl/string.h>

#include <array>

#include "arrays.hpp"
#include "gpugeom/voronoi_cells.hpp"

namespace gpugeom::py {
namespace {

using sz = std::size_t;

// Host points: computed on the executor the options pick, host arrays back; device points:
// computed on their device, the arrays left there.
nb::dict voronoi_cells_bind(const AnyArray& points, std::array<double, 3> lo,
                            std::array<double, 3> hi, std::array<bool, 3> periodic, bool polygons,
                            const std::string& backend, nb::handle stream, int threads) {
  const Input in = points_input(points, 3);
  auto o = options_for<VoronoiCellsOptions>(backend, stream, threads, in);
  for (int d = 0; d < 3; ++d) o.lo[d] = lo[d], o.hi[d] = hi[d], o.periodic[d] = periodic[d];
  o.polygons = polygons;
  const std::int64_t n = in.shape[0];
  nb::dict r;
  if (in.on_device) {
    const DeviceVoronoiCells c = unlocked([&] { return voronoi_cells_device(pts(in), n, o); });
    const DeviceOut out{c.backend, device_of(o)};
    const sz nf = sz(c.num_faces);
    r["volumes"] = out(c.volumes, {sz(n)});
    r["areas"] = out(c.areas, {sz(n)});
    r["centroids"] = out(c.centroids, {sz(n), 3});
    r["face_offsets"] = out(c.face_offsets, {sz(n) + 1});
    r["neighbors"] = out(c.neighbors, {nf});
    r["face_areas"] = out(c.face_areas, {nf});
    r["face_normals"] = out(c.face_normals, {nf, 3});
    r["face_vertex_offsets"] = out(c.face_vertex_offsets, {polygons ? nf + 1 : 0});
    r["face_vertices"] = out(c.face_vertices, {sz(c.num_face_vertices)});
    r["vertex_offsets"] = out(c.vertex_offsets, {polygons ? sz(n) + 1 : 0});
    r["vertices"] = out(c.vertices, {sz(c.num_vertices), 3});
    r["stats"] = stats_dict(c.stats);
    return r;
  }
  VoronoiCells c = unlocked([&] { return voronoi_cells(pts(in), n, o); });
  const sz nf = c.neighbors.size(), nfv = c.face_vertices.size(), nv = c.vertices.size() / 3;
  r["volumes"] = host_array(std::move(c.volumes), {sz(n)});
  r["areas"] = host_array(std::move(c.areas), {sz(n)});
  r["centroids"] = host_array(std::move(c.centroids), {sz(n), 3});
  r["face_offsets"] = host_array(std::move(c.face_offsets), {sz(n) + 1});
  r["neighbors"] = host_array(std::move(c.neighbors), {nf});
  r["face_areas"] = host_array(std::move(c.face_areas), {nf});
  r["face_normals"] = host_array(std::move(c.face_normals), {nf, 3});
  const sz nfo = c.face_vertex_offsets.size(), nvo = c.vertex_offsets.size();  // (0: no polygons)
  r["face_vertex_offsets"] = host_array(std::move(c.face_vertex_offsets), {nfo});
  r["face_vertices"] = host_array(std::move(c.face_vertices), {nfv});
  r["vertex_offsets"] = host_array(std::move(c.vertex_offsets), {nvo});
  r["vertices"] = host_array(std::move(c.vertices), {nv, 3});
  r["stats"] = stats_dict(c.stats);
  return r;
}

}  // namespace

void bind_cells(nb::module_& m) {
  using namespace nb::literals;
  m.def("voronoi_cells", &voronoi_cells_bind, "points"_a, "lo"_a, "hi"_a, "periodic"_a,
        "polygons"_a = true, "backend"_a = "auto", "stream"_a = 0, "threads"_a = 0,
        "Voronoi cells of (n, 3) points in the box [lo, hi], periodic per axis: a dict of flat "
        "arrays (gpugeom.VoronoiCells gives them names)");
}

}  // namespace gpugeom::py
