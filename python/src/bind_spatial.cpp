// Bindings of the point-set capabilities: 2D / 3D Delaunay, 2D Voronoi, 3D hull, point location
// and the exact checkers. Each takes the points where they are (host or CUDA device) and returns
// a dict of arrays in the same place.
#include <nanobind/stl/function.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <optional>

#include "arrays.hpp"
#include "gpugeom/blocks.hpp"
#include "gpugeom/cdt2d.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/delaunay3d.hpp"
#include "gpugeom/hull3d.hpp"
#include "gpugeom/locate.hpp"
#include "gpugeom/multi_gpu.hpp"
#include "gpugeom/spatial.hpp"
#include "gpugeom/voronoi3d.hpp"
#include "verify.hpp"

namespace gpugeom::py {

namespace {

using sz = std::size_t;

// A 2D triangulation on the host as the dict every 2D binding returns.
nb::dict triangulation2d_dict(Triangulation2d& t, std::int64_t n) {
  nb::dict r;
  const sz nt = t.num_triangles;
  t.triangles.resize(3 * nt);  // the host path may size them for the most triangles
  t.neighbors.resize(3 * nt);
  r["simplices"] = host_array(std::move(t.triangles), {nt, 3});
  r["neighbors"] = host_array(std::move(t.neighbors), {nt, 3});
  r["duplicate_of"] = host_array(std::move(t.duplicate_of), {sz(n)});
  r["stats"] = stats_dict(t.stats);
  return r;
}

// devices= (Delaunay(devices=...)): the blocks of several devices of this host read host points
// (each device takes its block's); checked before anything runs.
void check_devices_input(const Input& in, const std::optional<std::vector<int>>& devices) {
  if (devices && in.on_device)
    throw nb::value_error(
        "devices= takes host (NumPy) points: each device copies in its block's points");
}

nb::dict delaunay2d_bind(const AnyArray& points, const std::string& backend, nb::handle stream,
                         int threads, const std::string& method, std::int64_t grid,
                         std::optional<std::vector<int>> devices) {
  const Input in = points_input(points, 2);
  check_devices_input(in, devices);
  auto o = options_for<Delaunay2dOptions>(backend, stream, threads, in);
  o.method = parse_method(method);
  o.grid = grid;
  const std::int64_t n = in.shape[0];
  nb::dict r;
  if (devices) {
    Triangulation2d t = unlocked([&] { return delaunay2d_devices(pts(in), n, *devices, o); });
    return triangulation2d_dict(t, n);
  }
  if (in.on_device) {
    DeviceTriangulation2d t = unlocked([&] { return delaunay2d_device(pts(in), n, o); });
    const DeviceOut out{t.backend, device_of(o)};
    r["simplices"] = out(t.triangles, {sz(t.num_triangles), 3});
    r["neighbors"] = out(t.neighbors, {sz(t.num_triangles), 3});
    r["duplicate_of"] = out(t.duplicate_of, {sz(n)});
    r["stats"] = stats_dict(t.stats);
    return r;
  }
  Triangulation2d t = unlocked([&] { return delaunay2d(pts(in), n, o); });
  return triangulation2d_dict(t, n);
}

// A 2D triangulation kept between calls (Delaunay(incremental=True) in 2D; issue 47). Its
// arrays are where its first points were: new points must be there too (the Python layer
// converts them), and results come back there.
struct Dynamic2dState {
  static constexpr int kDim = 2;
  DynamicDelaunay2d t;
  bool on_device;
  int device;
  RunOptions run;  // its device and stream (the Voronoi diagram of it runs there too)
};

void dynamic2d_init(Dynamic2dState* self, const AnyArray& points, const std::string& backend,
                    nb::handle stream, int threads) {
  const Input in = points_input(points, 2);
  auto o = options_for<Delaunay2dOptions>(backend, stream, threads, in);
  const std::int64_t n = in.shape[0];
  DynamicDelaunay2d t = unlocked([&] {
    return in.on_device ? DynamicDelaunay2d::from_device(pts(in), n, o)
                        : DynamicDelaunay2d(pts(in), n, o);
  });
  new (self) Dynamic2dState{std::move(t), in.on_device, in.on_device ? device_of(o) : -1, o};
}

// New points (insert) or new coordinates (move) for a kept structure (Dynamic2dState,
// Dynamic3dState, DynamicHullState): where its first points were, host memory or its GPU.
template <class State>
Input kept_points_input(const State& self, const AnyArray& points) {
  const Input in = points_input(points, State::kDim);
  if (in.on_device != self.on_device)
    throw nb::value_error(self.on_device
                              ? "points must be on the GPU, as the first points were"
                              : "points must be in host memory, as the first points were");
  return in;
}

template <class State>
void dynamic_insert(State& self, const AnyArray& points) {
  const Input in = kept_points_input(self, points);
  const std::int64_t n = in.shape[0];
  unlocked([&] {
    if (in.on_device)
      self.t.insert_device(pts(in), n);
    else
      self.t.insert(pts(in), n);
  });
}

template <class State>
void dynamic_move(State& self, const AnyArray& points) {
  const Input in = kept_points_input(self, points);
  const std::int64_t n = in.shape[0];
  unlocked([&] {
    if (in.on_device)
      self.t.move_device(pts(in), n);
    else
      self.t.move(pts(in), n);
  });
}

// Removes points by index (int32, 1-D; host memory, or the triangulation's GPU).
template <class State>
void dynamic_remove(State& self, const AnyArray& indices) {
  const Input in = inspect(indices, "indices");
  if (in.shape.size() != 1) throw nb::value_error("indices must be 1-D");
  if (!holds<std::int32_t>(in)) throw nb::type_error("indices must be int32");
  if (in.on_device && !self.on_device)
    throw nb::value_error("indices must be in host memory, as the points are");
  const auto* p = static_cast<const std::int32_t*>(in.data);
  const std::int64_t n = in.shape[0];
  unlocked([&] {
    if (in.on_device)
      self.t.remove_device(p, n);
    else
      self.t.remove(p, n);
  });
}

// Which simplices the last update changed (the kept triangulation's changes()), where its
// arrays are.
template <class State>
nb::dict dynamic_changes(const State& self) {
  nb::dict r;
  if (self.on_device) {
    DeviceSimplexChanges c = unlocked([&] { return self.t.device_changes(); });
    const DeviceOut out{c.backend, self.device};
    r["previous_index"] = out(c.previous_index, {sz(c.num_simplices)});
    r["removed"] = out(c.removed, {sz(c.num_removed)});
    return r;
  }
  SimplexChanges c = unlocked([&] { return self.t.changes(); });
  r["previous_index"] = host_array(std::move(c.previous_index), {sz(c.num_simplices)});
  r["removed"] = host_array(std::move(c.removed), {sz(c.num_removed)});
  return r;
}

nb::dict dynamic2d_result(const Dynamic2dState& self) {
  nb::dict r;
  const std::int64_t n = self.t.num_points();
  if (self.on_device) {
    DeviceTriangulation2d t = unlocked([&] { return self.t.device_triangulation(); });
    const DeviceOut out{t.backend, self.device};
    r["simplices"] = out(t.triangles, {sz(t.num_triangles), 3});
    r["neighbors"] = out(t.neighbors, {sz(t.num_triangles), 3});
    r["duplicate_of"] = out(t.duplicate_of, {sz(n)});
    r["stats"] = stats_dict(t.stats);
    return r;
  }
  Triangulation2d t = unlocked([&] { return self.t.triangulation(); });
  return triangulation2d_dict(t, n);
}

// The options of a Voronoi diagram made from host arrays on the host threads (the kept
// triangulations' host results, the furthest-site triangulation): run's thread count.
template <class Options>
Options on_host(const RunOptions& run) {
  Options o;
  o.backend = Backend::Cpu;
  o.threads = run.threads;
  return o;
}

void put_voronoi_host(nb::dict& r, Voronoi2d& v, std::int64_t n) {
  const sz nv = v.vertices.size() / 2, nr = v.ridge_points.size() / 2;
  const sz ncv = v.cell_vertices.size(), nt = v.simplex_vertex.size();
  r["vertices"] = host_array(std::move(v.vertices), {nv, 2});
  r["ridge_points"] = host_array(std::move(v.ridge_points), {nr, 2});
  r["ridge_vertices"] = host_array(std::move(v.ridge_vertices), {nr, 2});
  r["ridge_directions"] = host_array(std::move(v.ridge_directions), {nr, 2});
  r["cell_offsets"] = host_array(std::move(v.cell_offsets), {sz(n) + 1});
  r["cell_vertices"] = host_array(std::move(v.cell_vertices), {ncv});
  r["simplex_vertex"] = host_array(std::move(v.simplex_vertex), {nt});
}

// A triangulation and its Voronoi diagram as a dict: where the device entries left them, or host
// arrays.
nb::dict voronoi_dict(DeviceTriangulation2d& t, DeviceVoronoi2d& v, std::int64_t n, int device) {
  nb::dict r;
  const DeviceOut out{v.backend, device};
  r["simplices"] = out(t.triangles, {sz(t.num_triangles), 3});
  r["duplicate_of"] = out(t.duplicate_of, {sz(n)});
  r["vertices"] = out(v.vertices, {sz(v.num_vertices), 2});
  r["ridge_points"] = out(v.ridge_points, {sz(v.num_ridges), 2});
  r["ridge_vertices"] = out(v.ridge_vertices, {sz(v.num_ridges), 2});
  r["ridge_directions"] = out(v.ridge_directions, {sz(v.num_ridges), 2});
  r["cell_offsets"] = out(v.cell_offsets, {sz(n) + 1});
  r["cell_vertices"] = out(v.cell_vertices, {sz(v.num_cell_vertices)});
  r["simplex_vertex"] = out(v.simplex_vertex, {sz(t.num_triangles)});
  r["stats"] = stats_dict(t.stats);
  return r;
}
nb::dict voronoi_dict(Triangulation2d& t, Voronoi2d& v, std::int64_t n) {
  nb::dict r;
  const sz nt = t.num_triangles;
  t.triangles.resize(3 * nt);
  r["simplices"] = host_array(std::move(t.triangles), {nt, 3});
  r["duplicate_of"] = host_array(std::move(t.duplicate_of), {sz(n)});
  put_voronoi_host(r, v, n);
  r["stats"] = stats_dict(t.stats);
  return r;
}

nb::dict voronoi2d_bind(const AnyArray& points, const std::string& backend, nb::handle stream,
                        int threads) {
  const Input in = points_input(points, 2);
  auto o = options_for<Delaunay2dOptions>(backend, stream, threads, in);
  const std::int64_t n = in.shape[0];
  if (in.on_device) {
    DeviceTriangulation2d t;
    DeviceVoronoi2d v;
    {
      nb::gil_scoped_release released;
      t = delaunay2d_device(pts(in), n, o);
      v = voronoi2d_device(pts(in), n, t, options_from<Voronoi2dOptions>(o));
    }
    return voronoi_dict(t, v, n, device_of(o));
  }
  Triangulation2d t;
  Voronoi2d v;
  {
    nb::gil_scoped_release released;
    v = voronoi2d(pts(in), n, o, &t, &t.stats);  // both on the executor, results back once
  }
  return voronoi_dict(t, v, n);
}

// The furthest-site Delaunay triangulation of host points (issue 49) and, with voronoi, its
// Voronoi diagram: host arrays (the Python layer moves them where the points were).
nb::dict furthest_site2d_bind(const AnyArray& points, int threads, bool voronoi) {
  const Input in = points_input(points, 2);
  if (in.on_device) throw nb::value_error("furthest_site2d takes host points");
  Delaunay2dOptions o;
  o.backend = Backend::Cpu;
  o.threads = threads;
  const std::int64_t n = in.shape[0];
  Triangulation2d t = unlocked([&] { return furthest_site_delaunay2d(pts(in), n, o); });
  if (voronoi) {
    Voronoi2d v = unlocked([&] { return voronoi2d(pts(in), n, t, on_host<Voronoi2dOptions>(o)); });
    return voronoi_dict(t, v, n);
  }
  return triangulation2d_dict(t, n);
}

// The Voronoi diagram of a kept 2D triangulation (Voronoi(incremental=True); issue 47), made from
// its current triangles where they are. points: its current points, where its first points were
// (the caller's copy; the diagram's vertices are their triangles' circumcentres). A removed point
// has an empty cell.
nb::dict dynamic_voronoi(const Dynamic2dState& self, const AnyArray& points) {
  const Input in = kept_points_input(self, points);
  const std::int64_t n = in.shape[0];
  if (n != self.t.num_points())
    throw nb::value_error("points must be the triangulation's current points");
  if (self.on_device) {
    DeviceTriangulation2d t;
    DeviceVoronoi2d v;
    {
      nb::gil_scoped_release released;
      t = self.t.device_triangulation();
      v = voronoi2d_device(pts(in), n, t, options_from<Voronoi2dOptions>(self.run));
    }
    return voronoi_dict(t, v, n, self.device);
  }
  Triangulation2d t;
  Voronoi2d v;
  {
    nb::gil_scoped_release released;
    t = self.t.triangulation();
    v = voronoi2d(pts(in), n, t, on_host<Voronoi2dOptions>(self.run));
  }
  return voronoi_dict(t, v, n);
}

// A 3D hull's arrays as a dict: where the device entry left them, or host arrays.
nb::dict hull_dict(DeviceHull3d h, int device) {
  nb::dict r;
  const DeviceOut out{h.backend, device};
  r["simplices"] = out(h.triangles, {sz(h.num_facets), 3});
  r["neighbors"] = out(h.neighbors, {sz(h.num_facets), 3});
  r["vertices"] = out(h.vertices, {sz(h.num_vertices)});
  r["equations"] = out(h.equations, {sz(h.num_facets), 4});
  r["stats"] = stats_dict(h.stats);
  return r;
}
nb::dict hull_dict(ConvexHull3d h) {
  nb::dict r;
  const sz nf = h.num_facets;
  h.triangles.resize(3 * nf);
  h.neighbors.resize(3 * nf);
  h.equations.resize(4 * nf);
  h.vertices.resize(sz(h.num_vertices));
  r["simplices"] = host_array(std::move(h.triangles), {nf, 3});
  r["neighbors"] = host_array(std::move(h.neighbors), {nf, 3});
  r["vertices"] = host_array(std::move(h.vertices), {sz(h.num_vertices)});
  r["equations"] = host_array(std::move(h.equations), {nf, 4});
  r["stats"] = stats_dict(h.stats);
  return r;
}

nb::dict hull3d_bind(const AnyArray& points, const std::string& backend, nb::handle stream,
                     int threads, const std::string& method, std::int64_t grid) {
  const Input in = points_input(points, 3);
  auto o = options_for<Hull3dOptions>(backend, stream, threads, in);
  o.method = parse_method(method);
  o.grid = grid;
  const std::int64_t n = in.shape[0];
  if (in.on_device)
    return hull_dict(unlocked([&] { return convex_hull3d_device(pts(in), n, o); }), device_of(o));
  return hull_dict(unlocked([&] { return convex_hull3d(pts(in), n, o); }));
}

// A 3D hull kept between calls (ConvexHull(incremental=True) in 3D; issue 47), as
// Dynamic2dState.
struct DynamicHullState {
  static constexpr int kDim = 3;
  DynamicHull3d t;
  bool on_device;
  int device;
};

void dynamic_hull_init(DynamicHullState* self, const AnyArray& points, const std::string& backend,
                       nb::handle stream, int threads, const std::string& method,
                       std::int64_t grid) {
  const Input in = points_input(points, 3);
  auto o = options_for<Hull3dOptions>(backend, stream, threads, in);
  o.method = parse_method(method);
  o.grid = grid;
  const std::int64_t n = in.shape[0];
  DynamicHull3d t = unlocked([&] {
    return in.on_device ? DynamicHull3d::from_device(pts(in), n, o) : DynamicHull3d(pts(in), n, o);
  });
  new (self) DynamicHullState{std::move(t), in.on_device, in.on_device ? device_of(o) : -1};
}

nb::dict dynamic_hull_result(const DynamicHullState& self) {
  if (self.on_device) return hull_dict(unlocked([&] { return self.t.device_hull(); }), self.device);
  return hull_dict(unlocked([&] { return self.t.hull(); }));
}

// A tetrahedralisation as the Python layer takes it: arrays where they are.
nb::dict tets_dict(DeviceTriangulation3d&& t, int device) {
  nb::dict r;
  const std::int64_t n = t.num_points;
  const DeviceOut out{t.backend, device};
  r["simplices"] = out(t.tetrahedra, {sz(t.num_tetrahedra), 4});
  r["neighbors"] = out(t.neighbors, {sz(t.num_tetrahedra), 4});
  r["duplicate_of"] = out(t.duplicate_of, {sz(n)});
  r["vertex_to_simplex"] = out(t.vertex_to_simplex, {sz(n)});
  r["hull_facets"] = out(t.hull_facets, {sz(t.num_hull_facets), 3});
  r["stats"] = stats_dict(t.stats);
  return r;
}
nb::dict tets_dict(Triangulation3d&& t) {
  nb::dict r;
  const sz n = t.duplicate_of.size(), nt = t.num_tetrahedra, nh = sz(t.num_hull_facets);
  t.tetrahedra.resize(4 * nt);
  t.neighbors.resize(4 * nt);
  t.hull_facets.resize(3 * nh);
  r["simplices"] = host_array(std::move(t.tetrahedra), {nt, 4});
  r["neighbors"] = host_array(std::move(t.neighbors), {nt, 4});
  r["duplicate_of"] = host_array(std::move(t.duplicate_of), {n});
  r["vertex_to_simplex"] = host_array(std::move(t.vertex_to_simplex), {n});
  r["hull_facets"] = host_array(std::move(t.hull_facets), {nh, 3});
  r["stats"] = stats_dict(t.stats);
  return r;
}

// A tetrahedralisation's simplices and duplicate map and its Voronoi diagram (issue 49) as a
// dict: where the device entries left them, or host arrays. "cell_*" are the regions.
nb::dict voronoi3d_dict(DeviceTriangulation3d& t, DeviceVoronoi3d& v, std::int64_t n, int device) {
  nb::dict r;
  const DeviceOut out{v.backend, device};
  r["simplices"] = out(t.tetrahedra, {sz(t.num_tetrahedra), 4});
  r["duplicate_of"] = out(t.duplicate_of, {sz(n)});
  r["vertices"] = out(v.vertices, {sz(v.num_vertices), 3});
  r["ridge_points"] = out(v.ridge_points, {sz(v.num_ridges), 2});
  r["ridge_offsets"] = out(v.ridge_offsets, {sz(v.num_ridges) + 1});
  r["ridge_vertices"] = out(v.ridge_vertices, {sz(v.num_ridge_vertices)});
  r["cell_offsets"] = out(v.region_offsets, {sz(n) + 1});
  r["cell_vertices"] = out(v.region_vertices, {sz(v.num_region_vertices)});
  r["simplex_vertex"] = out(v.simplex_vertex, {sz(t.num_tetrahedra)});
  r["stats"] = stats_dict(t.stats);
  return r;
}
nb::dict voronoi3d_dict(Triangulation3d& t, Voronoi3d& v, std::int64_t n) {
  nb::dict r;
  const sz nt = t.num_tetrahedra;
  t.tetrahedra.resize(4 * nt);
  r["simplices"] = host_array(std::move(t.tetrahedra), {nt, 4});
  r["duplicate_of"] = host_array(std::move(t.duplicate_of), {sz(n)});
  const sz nv = v.vertices.size() / 3, nr = v.ridge_points.size() / 2;
  const sz nrv = v.ridge_vertices.size(), ncv = v.region_vertices.size();
  r["vertices"] = host_array(std::move(v.vertices), {nv, 3});
  r["ridge_points"] = host_array(std::move(v.ridge_points), {nr, 2});
  r["ridge_offsets"] = host_array(std::move(v.ridge_offsets), {nr + 1});
  r["ridge_vertices"] = host_array(std::move(v.ridge_vertices), {nrv});
  r["cell_offsets"] = host_array(std::move(v.region_offsets), {sz(n) + 1});
  r["cell_vertices"] = host_array(std::move(v.region_vertices), {ncv});
  r["simplex_vertex"] = host_array(std::move(v.simplex_vertex), {nt});
  Delaunay3dStats st = t.stats;  // (the diagram's peak is the whole call's where it made both)
  st.device_peak_bytes = std::max(t.stats.device_peak_bytes, v.stats.device_peak_bytes);
  st.phase_ms.insert(st.phase_ms.end(), v.stats.phase_ms.begin(), v.stats.phase_ms.end());
  nb::dict d = stats_dict(st);
  nb::dict counters = nb::cast<nb::dict>(d["counters"]);  // (the diagram's beside the tetrahedra's)
  counters["voronoi_vertices"] = v.stats.voronoi_vertices;
  counters["voronoi_ridges"] = v.stats.voronoi_ridges;
  r["stats"] = d;
  return r;
}

// Host points: both structures on the executor the options pick, host results; device points:
// both where the points are.
nb::dict voronoi3d_bind(const AnyArray& points, const std::string& backend, nb::handle stream,
                        int threads) {
  const Input in = points_input(points, 3);
  auto o = options_for<Delaunay3dOptions>(backend, stream, threads, in);
  const std::int64_t n = in.shape[0];
  if (in.on_device) {
    DeviceTriangulation3d t;
    DeviceVoronoi3d v;
    {
      nb::gil_scoped_release released;
      t = delaunay3d_device(pts(in), n, o);
      v = voronoi3d_device(pts(in), n, t, options_from<Voronoi3dOptions>(o));
    }
    return voronoi3d_dict(t, v, n, device_of(o));
  }
  Triangulation3d t;
  Voronoi3d v;
  {
    nb::gil_scoped_release released;
    v = voronoi3d(pts(in), n, o, &t);  // both on the executor, results back once
  }
  return voronoi3d_dict(t, v, n);
}

// A 3D tetrahedralisation kept between calls (Delaunay(incremental=True) in 3D; issue 47), as
// Dynamic2dState. Ctrl-C ends a long insertion (KeyboardInterrupt), the object left as it was.
struct Dynamic3dState {
  static constexpr int kDim = 3;
  DynamicDelaunay3d t;
  bool on_device;
  int device;
  RunOptions run;  // (its device and stream: the Voronoi diagram runs there too)
};

void dynamic3d_init(Dynamic3dState* self, const AnyArray& points, const std::string& backend,
                    nb::handle stream, int threads) {
  const Input in = points_input(points, 3);
  auto o = options_for<Delaunay3dOptions>(backend, stream, threads, in);
  o.progress = [](const Delaunay3dProgress&) {
    nb::gil_scoped_acquire locked;
    if (PyErr_CheckSignals() != 0) throw nb::python_error();
  };
  const std::int64_t n = in.shape[0];
  DynamicDelaunay3d t = unlocked([&] {
    return in.on_device ? DynamicDelaunay3d::from_device(pts(in), n, o)
                        : DynamicDelaunay3d(pts(in), n, o);
  });
  new (self) Dynamic3dState{std::move(t), in.on_device, in.on_device ? device_of(o) : -1, o};
}

// The Voronoi diagram of a kept tetrahedralisation (Voronoi(incremental=True) in 3D), made from
// its current tetrahedra where they are; points: its current points, where its first were.
nb::dict dynamic_voronoi3d(const Dynamic3dState& self, const AnyArray& points) {
  const Input in = kept_points_input(self, points);
  const std::int64_t n = in.shape[0];
  if (n != self.t.num_points())
    throw nb::value_error("points must be the tetrahedralisation's current points");
  if (self.on_device) {
    DeviceTriangulation3d t;
    DeviceVoronoi3d v;
    {
      nb::gil_scoped_release released;
      t = self.t.device_tetrahedralisation();
      v = voronoi3d_device(pts(in), n, t, options_from<Voronoi3dOptions>(self.run));
    }
    return voronoi3d_dict(t, v, n, self.device);
  }
  Triangulation3d t;
  Voronoi3d v;
  {
    nb::gil_scoped_release released;
    t = self.t.tetrahedralisation();
    v = voronoi3d(pts(in), n, t, on_host<Voronoi3dOptions>(self.run));
  }
  return voronoi3d_dict(t, v, n);
}

nb::dict dynamic3d_result(const Dynamic3dState& self) {
  if (self.on_device)
    return tets_dict(unlocked([&] { return self.t.device_tetrahedralisation(); }), self.device);
  return tets_dict(unlocked([&] { return self.t.tetrahedralisation(); }));
}

nb::dict delaunay3d_bind(const AnyArray& points, const std::string& backend, nb::handle stream,
                         int threads, nb::object progress, const std::string& method,
                         std::int64_t grid, std::optional<std::vector<int>> devices) {
  const Input in = points_input(points, 3);
  check_devices_input(in, devices);
  auto o = options_for<Delaunay3dOptions>(backend, stream, threads, in);
  o.method = parse_method(method);
  o.grid = grid;
  // The progress callback runs on this thread with the interpreter locked again; it also lets a
  // Ctrl-C end the run (KeyboardInterrupt reaches the caller, nothing leaks).
  // (A borrowed handle: the caller holds the callable for the whole call, and the options may be
  // copied while the interpreter is unlocked, where no reference count may change.)
  PyObject* cb = progress.is_none() ? nullptr : progress.ptr();
  o.progress = [cb](const Delaunay3dProgress& p) {
    nb::gil_scoped_acquire locked;
    if (PyErr_CheckSignals() != 0) throw nb::python_error();
    if (cb) {
      nb::handle f(cb);
      f(nb::str(p.phase), p.inserted, p.total, p.batch);
    }
  };
  const std::int64_t n = in.shape[0];
  if (devices) {
    // (the blocks would report their own points' progress from their own threads, several
    // runs interleaved: refused)
    if (cb) throw nb::value_error("progress= is not taken with devices= (the blocks run at once)");
    return tets_dict(unlocked([&] { return delaunay3d_devices(pts(in), n, *devices, o); }));
  }
  if (in.on_device)
    return tets_dict(unlocked([&] { return delaunay3d_device(pts(in), n, o); }), device_of(o));
  return tets_dict(unlocked([&] { return delaunay3d(pts(in), n, o); }));
}

nb::object find_simplex_bind(const AnyArray& points, const AnyArray& simplices,
                             const AnyArray& neighbors, const AnyArray& queries, int threads) {
  Input p = inspect(points, "points");
  if (p.on_device || !holds<double>(p) || p.shape.size() != 2 ||
      (p.shape[1] != 2 && p.shape[1] != 3))
    throw nb::value_error("points must be a host float64 array of shape (n, 2) or (n, 3)");
  const int dim = int(p.shape[1]);
  std::int64_t ns = 0, nn = 0;
  const std::int32_t* s = cells_of(simplices, "simplices", dim + 1, &ns);
  const std::int32_t* nb_ = cells_of(neighbors, "neighbors", dim + 1, &nn);
  if (ns != nn) throw nb::value_error("simplices and neighbors differ in length");
  Input q = inspect(queries, "xi");
  if (q.on_device || !holds<double>(q) || q.shape.size() != 2 || q.shape[1] != dim)
    throw nb::value_error(
        ("xi must be a host float64 array of shape (m, " + std::to_string(dim) + ")").c_str());
  HostVector<std::int32_t> r;
  {
    nb::gil_scoped_release released;
    LocateOptions o;
    o.threads = threads;
    r = dim == 2 ? find_simplex2d(pts(p), p.shape[0], s, nb_, ns, pts(q), q.shape[0], o)
                 : find_simplex3d(pts(p), p.shape[0], s, nb_, ns, pts(q), q.shape[0], o);
  }
  return host_array(std::move(r), {sz(q.shape[0])});
}

// The constrained Delaunay triangulation of host points and segments (cdt2d.hpp); holes (h, 2)
// and regions (r, 3: x, y, attribute) as float64 arrays.
nb::dict cdt2d_bind(const AnyArray& points, const AnyArray& segments, const AnyArray& holes,
                    const AnyArray& regions, bool enclosed, bool split, const std::string& backend,
                    int threads) {
  std::int64_t n = 0, m = 0, nh = 0, nr = 0;
  const double* p = reals_of(points, "points", 2, &n);
  const std::int32_t* s = cells_of(segments, "segments", 2, &m);
  const double* h = reals_of(holes, "holes", 2, &nh);
  const double* g = reals_of(regions, "regions", 3, &nr);
  auto o = options_for<Cdt2dOptions>(backend, nb::int_(0), threads, inspect(points, "points"));
  o.domain = enclosed ? Cdt2dOptions::Domain::Enclosed : Cdt2dOptions::Domain::ConvexHull;
  o.crossings = split ? Cdt2dOptions::Crossings::Split : Cdt2dOptions::Crossings::Refuse;
  for (std::int64_t i = 0; i < nh; ++i) o.holes.push_back({h[2 * i], h[2 * i + 1]});
  for (std::int64_t i = 0; i < nr; ++i) o.regions.push_back({g[3 * i], g[3 * i + 1], g[3 * i + 2]});
  ConstrainedTriangulation2d t = unlocked([&] { return cdt2d(p, n, s, m, o); });
  const sz nt = t.num_triangles;
  nb::dict r;
  r["simplices"] = host_array(std::move(t.triangles), {nt, 3});
  r["neighbors"] = host_array(std::move(t.neighbors), {nt, 3});
  r["segment_of"] = host_array(std::move(t.segment_of), {nt, 3});
  const sz nd = t.duplicate_of.size(), nn = t.new_points.size() / 2;  // (n + new points)
  r["duplicate_of"] = host_array(std::move(t.duplicate_of), {nd});
  r["new_points"] = host_array(std::move(t.new_points), {nn, 2});
  r["new_point_segments"] = host_array(std::move(t.new_point_segments), {nn, 2});
  if (!t.attribute.empty()) r["attribute"] = host_array(std::move(t.attribute), {nt});
  r["zero_length_segments"] = t.zero_length_segments;
  r["repeated_segments"] = t.repeated_segments;
  r["removed_triangles"] = t.removed_triangles;
  r["stats"] = stats_dict(t.stats);
  return r;
}

// The same from points and segments in CUDA device memory (or host memory with backend "cpu"),
// the results left there (cdt2d_device).
nb::dict cdt2d_device_bind(const AnyArray& points, const AnyArray& segments, const AnyArray& holes,
                           const AnyArray& regions, bool enclosed, const std::string& backend,
                           nb::handle stream, int threads) {
  const Input p = points_input(points, 2), sg = inspect(segments, "segments");
  if (!holds<std::int32_t>(sg) || sg.shape.size() != 2 || sg.shape[1] != 2)
    throw nb::value_error("segments must be an int32 array of shape (m, 2)");
  if (sg.on_device != p.on_device)
    throw nb::value_error("points and segments must be in the same memory (both on the device)");
  std::int64_t nh = 0, nr = 0;
  const double* h = reals_of(holes, "holes", 2, &nh);
  const double* g = reals_of(regions, "regions", 3, &nr);
  auto o = options_for<Cdt2dOptions>(backend, stream, threads, p);
  o.domain = enclosed ? Cdt2dOptions::Domain::Enclosed : Cdt2dOptions::Domain::ConvexHull;
  for (std::int64_t i = 0; i < nh; ++i) o.holes.push_back({h[2 * i], h[2 * i + 1]});
  for (std::int64_t i = 0; i < nr; ++i) o.regions.push_back({g[3 * i], g[3 * i + 1], g[3 * i + 2]});
  const std::int64_t n = p.shape[0], m = sg.shape[0];
  DeviceConstrainedTriangulation2d t = unlocked(
      [&] { return cdt2d_device(pts(p), n, static_cast<const std::int32_t*>(sg.data), m, o); });
  const DeviceOut out{t.backend, device_of(o)};
  const sz nt = sz(t.num_triangles);
  nb::dict r;
  r["simplices"] = out(t.triangles, {nt, 3});
  r["neighbors"] = out(t.neighbors, {nt, 3});
  r["segment_of"] = out(t.segment_of, {nt, 3});
  r["duplicate_of"] = out(t.duplicate_of, {sz(n)});
  if (t.attribute) r["attribute"] = out(t.attribute, {nt});
  r["zero_length_segments"] = t.zero_length_segments;
  r["repeated_segments"] = t.repeated_segments;
  r["removed_triangles"] = t.removed_triangles;
  r["stats"] = stats_dict(t.stats);
  return r;
}

// The extreme points of a 2D Delaunay triangulation's points, counter-clockwise (host arrays).
nb::object hull2d_bind(const AnyArray& points, const AnyArray& simplices,
                       const AnyArray& neighbors) {
  Input p = inspect(points, "points");
  if (p.on_device || !holds<double>(p) || p.shape.size() != 2 || p.shape[1] != 2)
    throw nb::value_error("points must be a host float64 array of shape (n, 2)");
  std::int64_t ns = 0, nn = 0;
  const std::int32_t* s = cells_of(simplices, "simplices", 3, &ns);
  const std::int32_t* nb_ = cells_of(neighbors, "neighbors", 3, &nn);
  if (ns != nn) throw nb::value_error("simplices and neighbors differ in length");
  HostVector<std::int32_t> v =
      unlocked([&] { return convex_hull2d_vertices(pts(p), p.shape[0], s, nb_, ns); });
  const sz h = v.size();
  return host_array(std::move(v), {h});
}

// gpugeom.dask's passes (include/gpugeom/blocks.hpp) take host arrays, checked here once: the
// library reads their indices unchecked. Points: float64 (n, 2) or (n, 3).
const double* host_points(const AnyArray& points, int* dim, std::int64_t* n) {
  Input p = inspect(points, "points");
  if (p.on_device || !holds<double>(p) || p.shape.size() != 2 ||
      (p.shape[1] != 2 && p.shape[1] != 3))
    throw nb::value_error("points must be a host float64 array of shape (n, 2) or (n, 3)");
  *dim = int(p.shape[1]);
  *n = p.shape[0];
  return pts(p);
}

// A host bool (or uint8) array of bytes, one per `per` (`n` of them in all, whatever its shape;
// -1: a 1D array of any length, written to `*count`): the masks the passes read unchecked.
const std::uint8_t* host_mask(const AnyArray& a, const char* name, std::int64_t n, const char* per,
                              std::int64_t* count = nullptr) {
  Input w = inspect(a, name);
  std::int64_t size = 1;
  for (auto e : w.shape) size *= e;
  if (w.on_device || !(holds<bool>(w) || holds<std::uint8_t>(w)) ||
      (n < 0 ? w.shape.size() != 1 : size != n))
    throw nb::value_error(
        (std::string(name) + " must be a host bool array with an entry per " + per).c_str());
  if (count) *count = size;
  return static_cast<const std::uint8_t*>(w.data);
}

// A host int64 array of the given shape (-1: any) whose entries lie in [lo, hi), checked once
// here: the library reads indices unchecked.
template <class T>
const T* host_indices_of(const AnyArray& a, const char* name, std::int64_t rows, std::int64_t cols,
                         std::int64_t lo, std::int64_t hi, std::int64_t* count = nullptr,
                         const char* kinds = "int64") {
  Input in = inspect(a, name);
  const bool shaped = cols < 0 ? in.shape.size() == 1 : in.shape.size() == 2 && in.shape[1] == cols;
  if (in.on_device || !holds<T>(in) || !shaped || (rows >= 0 && in.shape[0] != rows))
    throw nb::value_error((std::string(name) + " must be a host " + kinds + " array of shape (" +
                           (rows >= 0 ? std::to_string(rows) : std::string("k")) +
                           (cols >= 0 ? ", " + std::to_string(cols) : std::string(",")) + ")")
                              .c_str());
  const auto* p = static_cast<const T*>(in.data);
  const std::int64_t total = in.shape[0] * (cols < 0 ? 1 : cols);
  std::int64_t bad = 0;
  if (lo > INT64_MIN || hi < INT64_MAX) {
    // on the caller's OpenMP threads: a GPU block's arrays hold 10^8 indices
    nb::gil_scoped_release unlocked_here;
#pragma omp parallel for schedule(static) reduction(+ : bad)
    for (std::int64_t i = 0; i < total; ++i)
      bad += (std::int64_t(p[i]) < lo || std::int64_t(p[i]) >= hi) ? 1 : 0;
  }
  if (bad) throw nb::value_error((std::string(name) + ": an index out of range").c_str());
  if (count) *count = in.shape[0];
  return p;
}

// A host int64 array of the given shape (-1: any) whose entries lie in [lo, hi), checked once
// here: the library reads indices unchecked.
const std::int64_t* host_indices(const AnyArray& a, const char* name, std::int64_t rows,
                                 std::int64_t cols, std::int64_t lo, std::int64_t hi,
                                 std::int64_t* count = nullptr) {
  return host_indices_of<std::int64_t>(a, name, rows, cols, lo, hi, count);
}

// Calls f with a value of the index type of simplices (and neighbours): int32, as a
// triangulation gives them, or int64.
template <class F>
auto by_index_type(const AnyArray& simplices, F&& f) {
  Input in = inspect(simplices, "simplices");
  return holds<std::int32_t>(in) ? f(std::int32_t{}) : f(std::int64_t{});
}

// gpugeom.dask's bulk finality test of a block's simplices (include/gpugeom/blocks.hpp): host
// arrays, one byte per listed simplex.
nb::object circumballs_inside_bind(const AnyArray& points, const AnyArray& simplices,
                                   const AnyArray& rows, const std::vector<double>& region_lo,
                                   const std::vector<double>& region_hi,
                                   const std::vector<double>& bounds_lo,
                                   const std::vector<double>& bounds_hi, double scale,
                                   int threads) {
  int dim = 0;
  std::int64_t n = 0, m = 0, k = 0;
  const double* x = host_points(points, &dim, &n);
  BlockBoxes b;
  for (const auto* v : {&region_lo, &region_hi, &bounds_lo, &bounds_hi})
    if (int(v->size()) != dim) throw nb::value_error("each box corner needs dim coordinates");
  for (int j = 0; j < dim; ++j) {
    b.region_lo[j] = region_lo[j], b.region_hi[j] = region_hi[j];
    b.bounds_lo[j] = bounds_lo[j], b.bounds_hi[j] = bounds_hi[j];
  }
  b.scale = scale;
  return by_index_type(simplices, [&](auto index) {
    using T = decltype(index);
    const T* sx =
        host_indices_of<T>(simplices, "simplices", -1, dim + 1, 0, n, &m, "int32 or int64");
    const std::int64_t* rw = host_indices(rows, "rows", -1, -1, 0, m, &k);
    HostVector<std::uint8_t> out(static_cast<sz>(k));
    unlocked([&] { circumballs_inside_region(x, dim, sx, rw, k, b, out.data(), threads); });
    return host_array(std::move(out), {sz(k)});
  });
}

// gpugeom.dask's block passes (include/gpugeom/blocks.hpp) on host arrays: what a block
// requires of its triangulation, and the output of its owned simplices.
nb::dict block_required_bind(const AnyArray& simplices, const AnyArray& neighbors,
                             const AnyArray& owned, int threads) {
  std::int64_t n = 0;
  const std::uint8_t* own = host_mask(owned, "owned", -1, "point", &n);
  Input si = inspect(simplices, "simplices");
  if (si.shape.size() != 2 || (si.shape[1] != 3 && si.shape[1] != 4))
    throw nb::value_error("simplices must have shape (m, 3) or (m, 4)");
  const int d1 = int(si.shape[1]);
  std::int64_t m = 0;
  BlockRequired r = by_index_type(simplices, [&](auto index) {
    using T = decltype(index);
    const T* s = host_indices_of<T>(simplices, "simplices", -1, d1, 0, n, &m, "int32 or int64");
    const T* nbr = host_indices_of<T>(neighbors, "neighbors", m, d1, -1, m, nullptr,
                                      "int32 or int64 (as simplices)");
    return unlocked([&] { return block_required(s, nbr, m, d1 - 1, own, threads); });
  });
  nb::dict out;
  const sz k = r.owned_rows.size();
  out["owned_rows"] = host_array(std::move(r.owned_rows), {k});
  out["required"] = host_array(std::move(r.required), {sz(m)});
  return out;
}

nb::dict block_output_bind(const AnyArray& simplices, const AnyArray& neighbors,
                           const AnyArray& rows, const AnyArray& ids, const AnyArray& blk,
                           std::optional<AnyArray> points, int threads) {
  std::int64_t n = 0, m = 0, k = 0;
  // (32-bit, as the output: gpugeom.dask's ids lie below 2^31 - 1)
  const std::int32_t* id =
      host_indices_of<std::int32_t>(ids, "ids", -1, -1, 0, INT32_MAX, &n, "int32");
  const std::int32_t* bk =
      host_indices_of<std::int32_t>(blk, "blk", n, -1, 0, INT32_MAX, nullptr, "int32");
  const double* xyz = nullptr;
  int pdim = 0;
  if (points) {
    std::int64_t np_ = 0;
    xyz = host_points(*points, &pdim, &np_);
    if (np_ != n) throw nb::value_error("points must have a row per id");
  }
  Input si = inspect(simplices, "simplices");
  if (si.shape.size() != 2 || (si.shape[1] != 3 && si.shape[1] != 4))
    throw nb::value_error("simplices must have shape (m, 3) or (m, 4)");
  const int d1 = int(si.shape[1]);
  if (xyz && pdim != d1 - 1) throw nb::value_error("points must have the simplices' dimension");
  BlockOutput r = by_index_type(simplices, [&](auto index) {
    using T = decltype(index);
    const T* s = host_indices_of<T>(simplices, "simplices", -1, d1, 0, n, &m, "int32 or int64");
    const T* nbr = host_indices_of<T>(neighbors, "neighbors", m, d1, -1, m, nullptr,
                                      "int32 or int64 (as simplices)");
    const std::int64_t* rw = host_indices(rows, "rows", -1, -1, 0, m, &k);
    return unlocked(
        [&] { return block_output(s, nbr, m, d1 - 1, rw, k, id, bk, xyz, n, threads); });
  });
  nb::dict out;
  const sz q = r.request_owner.size(), nv = r.vertices.size();
  out["simplices"] = host_array(std::move(r.simplices), {sz(k), sz(d1)});
  out["nb_local"] = host_array(std::move(r.neighbors), {sz(k), sz(d1)});
  out["req_owner"] = host_array(std::move(r.request_owner), {q});
  out["req_key"] = host_array(std::move(r.request_key), {q, sz(d1 - 1)});
  out["req_pos"] = host_array(std::move(r.request_pos), {q});
  out["req_open"] = host_array(std::move(r.request_open), {q});
  out["used"] = host_array(std::move(r.vertices), {nv});
  out["vertices"] = host_array(std::move(r.vertex_ids), {nv});
  if (xyz) out["vertex_points"] = host_array(std::move(r.vertex_points), {nv, sz(d1 - 1)});
  return out;
}

// A grid of cells from Python's lists, checked.
CellGrid cell_grid(const std::vector<double>& lo, const std::vector<double>& width,
                   const std::vector<std::int64_t>& counts, int dim) {
  if (int(lo.size()) != dim || int(width.size()) != dim || int(counts.size()) != dim)
    throw nb::value_error("lo, width and counts need dim entries each");
  CellGrid g;
  for (int j = 0; j < dim; ++j) {
    if (counts[j] < 1 || !(width[j] >= 0) || counts[j] > (std::int64_t(1) << 20))
      throw nb::value_error("bad grid: counts must lie in [1, 2^20] and widths be >= 0");
    g.lo[j] = lo[j], g.width[j] = width[j], g.counts[j] = counts[j];
  }
  return g;
}

// The face requests that come to one block paired (each key twice): per request its partner's
// position.
nb::object match_faces_bind(const AnyArray& keys, const AnyArray& positions, const AnyArray& open,
                            int threads) {
  Input ki = inspect(keys, "keys");
  if (ki.shape.size() != 2 || (ki.shape[1] != 2 && ki.shape[1] != 3))
    throw nb::value_error("keys must have shape (q, 2) or (q, 3)");
  const std::int64_t dim = ki.shape[1];
  std::int64_t q = 0;
  // (int32 keys as a block's output gives them, or int64)
  HostVector<std::int64_t> r = by_index_type(keys, [&](auto index) {
    using T = decltype(index);
    const T* k = host_indices_of<T>(keys, "keys", -1, dim, 0, INT64_MAX, &q, "int32 or int64");
    const std::int64_t* p = host_indices(positions, "positions", q, -1, 0, INT64_MAX);
    const std::uint8_t* op = host_mask(open, "open", q, "request");
    return unlocked([&] { return match_faces(k, p, op, q, int(dim), threads); });
  });
  return host_array(std::move(r), {sz(q)});
}

// The neighbours of a block's output in global simplex indices: its -2 faces answered (their
// positions, and the global index of the simplex across each); int32 unless `wide` (a result of
// 2^31 simplices or more).
nb::object block_neighbors_bind(const AnyArray& nb_local, std::int64_t offset, const AnyArray& pos,
                                const AnyArray& across, bool wide, int threads) {
  Input nl = inspect(nb_local, "nb_local");
  if (nl.shape.size() != 2 || (nl.shape[1] != 3 && nl.shape[1] != 4))
    throw nb::value_error("nb_local must have shape (m, 3) or (m, 4)");
  const std::int64_t d1 = nl.shape[1];
  std::int64_t m = 0, q = 0;
  const std::int32_t* nbr =
      host_indices_of<std::int32_t>(nb_local, "nb_local", -1, d1, -2, INT32_MAX, &m, "int32");
  const std::int64_t* ps = host_indices(pos, "pos", -1, -1, 0, INT64_MAX, &q);
  const std::int64_t* ac = host_indices(across, "across", q, -1, -1, INT64_MAX);
  if (wide) {
    HostVector<std::int64_t> r = unlocked([&] {
      return block_neighbors<std::int64_t>(nbr, m, int(d1) - 1, offset, ps, ac, q, threads);
    });
    return host_array(std::move(r), {sz(m), sz(d1)});
  }
  HostVector<std::int32_t> r = unlocked([&] {
    return block_neighbors<std::int32_t>(nbr, m, int(d1) - 1, offset, ps, ac, q, threads);
  });
  return host_array(std::move(r), {sz(m), sz(d1)});
}

// What a block sends the others: per target block, the local indices of its own points; with
// the region and the bounds, the first finality test of its stars too (on the same balls).
nb::dict block_borders_bind(const AnyArray& points, const AnyArray& simplices,
                            const AnyArray& neighbors, const AnyArray& owned, std::int64_t block,
                            const std::vector<double>& lo, const std::vector<double>& width,
                            const std::vector<std::int64_t>& counts, double margin, double scale,
                            std::optional<std::vector<double>> region_lo,
                            std::optional<std::vector<double>> region_hi,
                            std::optional<std::vector<double>> bounds_lo,
                            std::optional<std::vector<double>> bounds_hi, int threads) {
  int dim = 0;
  std::int64_t n = 0, m = 0;
  const double* x = host_points(points, &dim, &n);
  const std::uint8_t* own = host_mask(owned, "owned", n, "point");
  const CellGrid g = cell_grid(lo, width, counts, dim);
  const bool test = region_lo.has_value();
  if (region_hi.has_value() != test || bounds_lo.has_value() != test ||
      bounds_hi.has_value() != test)
    throw nb::value_error("region_lo, region_hi, bounds_lo and bounds_hi go together");
  BlockBoxes b;
  if (test) {
    for (const auto* v : {&*region_lo, &*region_hi, &*bounds_lo, &*bounds_hi})
      if (int(v->size()) != dim) throw nb::value_error("each box corner needs dim coordinates");
    for (int j = 0; j < dim; ++j) {
      b.region_lo[j] = (*region_lo)[j], b.region_hi[j] = (*region_hi)[j];
      b.bounds_lo[j] = (*bounds_lo)[j], b.bounds_hi[j] = (*bounds_hi)[j];
    }
    b.scale = scale;
  }
  HostVector<std::uint8_t> inside;
  BlockBorders r = by_index_type(simplices, [&](auto index) {
    using T = decltype(index);
    const T* s =
        host_indices_of<T>(simplices, "simplices", -1, dim + 1, 0, n, &m, "int32 or int64");
    const T* nbr = host_indices_of<T>(neighbors, "neighbors", m, dim + 1, -1, m, nullptr,
                                      "int32 or int64 (as simplices)");
    if (test) inside.resize(static_cast<sz>(m));
    return unlocked([&] {
      return block_borders(x, dim, s, nbr, m, n, own, block, g, margin, scale, test ? &b : nullptr,
                           test ? inside.data() : nullptr, threads);
    });
  });
  nb::dict out;
  const sz t = r.targets.size(), v = r.vertices.size();
  out["targets"] = host_array(std::move(r.targets), {t});
  out["offsets"] = host_array(std::move(r.offsets), {sz(r.offsets.size())});
  out["vertices"] = host_array(std::move(r.vertices), {v});
  if (test) out["inside"] = host_array(std::move(inside), {sz(m)});
  return out;
}

// The bounds of a piece of gpugeom.dask's input and its first point that is not finite.
nb::dict point_bounds_bind(const AnyArray& points, int threads) {
  int dim = 0;
  std::int64_t n = 0;
  const double* x = host_points(points, &dim, &n);
  PointBounds r = unlocked([&] { return point_bounds(x, dim, n, threads); });
  nb::dict out;
  out["lo"] = std::vector<double>(r.lo, r.lo + dim);
  out["hi"] = std::vector<double>(r.hi, r.hi + dim);
  out["first_bad"] = r.first_bad;
  return out;
}

// How many points lie in each cell of a grid (gpugeom.dask's bins of the points a block lacks).
nb::object cell_counts_bind(const AnyArray& points, const std::vector<double>& lo,
                            const std::vector<double>& width,
                            const std::vector<std::int64_t>& counts, int threads) {
  int dim = 0;
  std::int64_t n = 0;
  const double* x = host_points(points, &dim, &n);
  CellGrid g = cell_grid(lo, width, counts, dim);
  HostVector<std::int32_t> r = unlocked([&] { return cell_counts(x, dim, n, g, threads); });
  std::vector<sz> shape(counts.begin(), counts.end());
  return host_array(std::move(r), shape);
}

// An empty_frontiers dict back as BlockFrontiers (its arrays copied: a few per cent of the bins).
BlockFrontiers frontiers_from(nb::handle d, int dim, std::int64_t blocks) {
  BlockFrontiers f;
  f.grid =
      cell_grid(nb::cast<std::vector<double>>(d["lo"]), nb::cast<std::vector<double>>(d["width"]),
                nb::cast<std::vector<std::int64_t>>(d["counts"]), dim);
  std::int64_t total = 1;
  for (int j = 0; j < dim; ++j) total *= f.grid.counts[j];
  std::int64_t k = 0;
  const std::int64_t* off = host_indices(nb::cast<AnyArray>(d["offsets"]), "frontier offsets",
                                         blocks + 1, -1, 0, INT64_MAX);
  const std::int64_t* bins =
      host_indices(nb::cast<AnyArray>(d["bins"]), "frontier bins", -1, -1, 0, total, &k);
  if (off[blocks] != k) throw nb::value_error("the frontier offsets do not end at its bins' count");
  f.offsets.assign(off, off + blocks + 1);
  f.bins.assign(bins, bins + k);
  return f;
}

// empty_frontiers as a dict: "offsets", "bins", "points" (int64 arrays) and the bins' grid
// ("lo", "width", "counts" lists), which split_to_blocks takes back as it is.
nb::dict empty_frontiers_bind(const AnyArray& counts, const std::vector<double>& lo,
                              const std::vector<double>& width,
                              const std::vector<std::int64_t>& shape, const AnyArray& region_lo,
                              const AnyArray& region_hi, std::int64_t cap, double band,
                              int threads) {
  const int dim = int(shape.size());
  if (dim != 2 && dim != 3) throw nb::value_error("the bins' grid must have 2 or 3 axes");
  CellGrid g = cell_grid(lo, width, shape, dim);
  std::int64_t total = 1;
  for (int j = 0; j < dim; ++j) total *= shape[std::size_t(j)];
  Input c = inspect(counts, "counts");
  std::int64_t size = 1;
  for (auto e : c.shape) size *= e;
  if (c.on_device || !holds<std::int32_t>(c) || size != total)
    throw nb::value_error("counts must be a host int32 array with an entry per bin");
  Input l = inspect(region_lo, "region_lo"), h = inspect(region_hi, "region_hi");
  for (const Input* b : {&l, &h})
    if (b->on_device || !holds<double>(*b) || b->shape.size() != 2 || b->shape[1] != dim ||
        b->shape[0] != l.shape[0])
      throw nb::value_error(
          "region_lo and region_hi must be host float64 arrays of shape (k, dim)");
  BlockFrontiers f = unlocked([&] {
    return empty_frontiers(static_cast<const std::int32_t*>(c.data), g, dim, pts(l), pts(h),
                           l.shape[0], cap, band, threads);
  });
  nb::dict out;
  const sz nb_ = f.points.size(), nbins = f.bins.size();
  out["offsets"] = host_array(std::move(f.offsets), {nb_ + 1});
  out["bins"] = host_array(std::move(f.bins), {nbins});
  out["points"] = host_array(std::move(f.points), {nb_});
  out["lo"] = lo, out["width"] = width, out["counts"] = shape;
  return out;
}

// The split of points to the blocks of gpugeom.dask's grid: by cell, and (box_lo, box_hi,
// box_block given) to every block with a box holding them, and (frontiers given: an
// empty_frontiers dict) to every block that takes their bin; `wanted`: the blocks to list.
nb::dict split_to_blocks_bind(const AnyArray& points, const std::vector<double>& lo,
                              const std::vector<double>& width,
                              const std::vector<std::int64_t>& counts,
                              std::optional<AnyArray> box_lo, std::optional<AnyArray> box_hi,
                              std::optional<AnyArray> box_block, std::optional<AnyArray> wanted,
                              bool gather, int threads, nb::object frontiers) {
  int dim = 0;
  std::int64_t n = 0;
  const double* x = host_points(points, &dim, &n);
  CellGrid g = cell_grid(lo, width, counts, dim);
  std::int64_t cells = 1;
  for (int j = 0; j < dim; ++j) cells *= counts[j];
  std::optional<BlockFrontiers> fr;
  if (!frontiers.is_none()) fr = frontiers_from(frontiers, dim, cells);
  if (box_lo.has_value() != box_hi.has_value() || box_lo.has_value() != box_block.has_value())
    throw nb::value_error("box_lo, box_hi and box_block go together");
  const double *bl = nullptr, *bh = nullptr;
  const std::int64_t* bb = nullptr;
  std::int64_t nboxes = 0;
  if (box_lo) {
    bb = host_indices(*box_block, "box_block", -1, -1, 0, cells, &nboxes);
    Input l = inspect(*box_lo, "box_lo"), h = inspect(*box_hi, "box_hi");
    for (const Input* b : {&l, &h})
      if (b->on_device || !holds<double>(*b) || b->shape.size() != 2 || b->shape[1] != dim ||
          b->shape[0] != nboxes)
        throw nb::value_error("box_lo and box_hi must be host float64 arrays of shape (k, dim)");
    bl = pts(l), bh = pts(h);
  }
  const std::uint8_t* want = nullptr;
  if (wanted) want = host_mask(*wanted, "wanted", cells, "block");
  CellSplit r = unlocked([&] {
    CellSplit split =
        split_to_blocks(x, dim, n, g, bl, bh, bb, nboxes, want, threads, fr ? &*fr : nullptr);
    if (gather) gather_blocks(x, dim, split, threads);
    return split;
  });
  nb::dict out;
  const sz total = r.order.size();
  if (gather) {
    out["points"] = host_array(std::move(r.points), {total, sz(dim)});
    out["cells"] = host_array(std::move(r.cells), {total});
  }
  out["cell"] = host_array(std::move(r.cell), {sz(n)});
  out["order"] = host_array(std::move(r.order), {total});
  out["cuts"] = host_array(std::move(r.cuts), {sz(cells + 1)});
  return out;
}

// gpugeom.dask's test of balls (centres, reaches, cut boxes) against the bins with points a
// block lacks (`marked`, one byte a bin of the grid (lo, width, counts)).
nb::object balls_in_bins_bind(const AnyArray& centres, const AnyArray& reach, const AnyArray& lo,
                              const AnyArray& hi, const std::vector<double>& grid_lo,
                              const std::vector<double>& width,
                              const std::vector<std::int64_t>& counts, const AnyArray& marked,
                              double margin, int threads) {
  int dim = 0;
  std::int64_t m = 0;
  const double* c = host_points(centres, &dim, &m);
  CellGrid g = cell_grid(grid_lo, width, counts, dim);
  std::int64_t cells = 1;
  for (int j = 0; j < dim; ++j) cells *= counts[std::size_t(j)];
  Input r = inspect(reach, "reach"), l = inspect(lo, "lo"), h = inspect(hi, "hi");
  if (r.on_device || !holds<double>(r) || r.shape.size() != 1 || r.shape[0] != m)
    throw nb::value_error("reach must be a host float64 array with one entry per centre");
  for (const Input* b : {&l, &h})
    if (b->on_device || !holds<double>(*b) || b->shape.size() != 2 || b->shape[0] != m ||
        b->shape[1] != dim)
      throw nb::value_error("lo and hi must be host float64 arrays shaped as the centres");
  const std::uint8_t* mk = host_mask(marked, "marked", cells, "bin");
  HostVector<std::uint8_t> out = unlocked(
      [&] { return balls_in_bins(c, pts(r), pts(l), pts(h), m, dim, g, mk, margin, threads); });
  return host_array(std::move(out), {sz(m)});
}

// The permutation that puts host points in Hilbert-curve order (ties keep their order):
// gpugeom.dask's blocks put their local points in it, so that the passes over their simplices
// read nearby points (in the input's order a random input made every vertex read a cache miss).
nb::object hilbert_order_bind(const AnyArray& points) {
  int dim = 0;
  std::int64_t n = 0;
  const double* x = host_points(points, &dim, &n);
  std::vector<std::int32_t> order = unlocked([&] {
    if (dim == 2) {
      std::vector<Point2> p(static_cast<std::size_t>(n));
      for (std::int64_t i = 0; i < n; ++i) p[std::size_t(i)] = {x[2 * i], x[2 * i + 1]};
      return hilbert_order(p, Backend::Cpu);
    }
    std::vector<Point3> p(static_cast<std::size_t>(n));
    for (std::int64_t i = 0; i < n; ++i) p[std::size_t(i)] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
    return hilbert_order(p, Backend::Cpu);
  });
  HostVector<std::int64_t> out(order.begin(), order.end());
  return host_array(std::move(out), {sz(n)});
}

nb::object hull_candidates2d_bind(const AnyArray& points, int threads) {
  Input p = inspect(points, "points");
  if (p.on_device || !holds<double>(p) || p.shape.size() != 2 || p.shape[1] != 2)
    throw nb::value_error("points must be a host float64 array of shape (n, 2)");
  HostVector<std::int64_t> v =
      unlocked([&] { return hull_candidates2d(pts(p), p.shape[0], threads); });
  const sz k = v.size();
  return host_array(std::move(v), {k});
}

// The independent exact checkers (src/verify), for tests and for users who want proof.
std::pair<bool, std::string> check_bind(const std::string& what, const AnyArray& points,
                                        const AnyArray& cells, nb::object duplicate_of,
                                        nb::object segments) {
  Input p = inspect(points, "points");
  if (p.on_device || !holds<double>(p) || p.shape.size() != 2)
    throw nb::value_error("points must be a host float64 array of shape (n, dim)");
  const std::int64_t n = p.shape[0];
  const int k = what == "delaunay3d" ? 4 : 3;
  std::int64_t nc = 0;
  const std::int32_t* c = cells_of(cells, "simplices", k, &nc);
  const std::int32_t* dup = nullptr;
  std::unique_ptr<AnyArray> keep;
  if (!duplicate_of.is_none()) {
    keep = std::make_unique<AnyArray>(nb::cast<AnyArray>(duplicate_of));
    Input d = inspect(*keep, "duplicate_of");
    if (d.on_device || !holds<std::int32_t>(d) || d.shape.size() != 1 || d.shape[0] != n)
      throw nb::value_error("duplicate_of must be a host int32 array of length n");
    dup = static_cast<const std::int32_t*>(d.data);
  }
  verify::Report rep;
  const std::int32_t* sg = nullptr;
  std::int64_t ns = 0;
  if (!segments.is_none()) sg = cells_of(nb::cast<AnyArray>(segments), "segments", 2, &ns);
  {
    nb::gil_scoped_release released;
    if (what == "cdt2d" && p.shape[1] == 2)
      rep = verify::check_constrained_delaunay2d(pts(p), n, c, nc, sg, ns, dup);
    else if (what == "delaunay2d" && p.shape[1] == 2)
      rep = verify::check_delaunay2d(pts(p), n, c, nc, dup);
    else if (what == "delaunay3d" && p.shape[1] == 3)
      rep = verify::check_delaunay3d(pts(p), n, c, nc, dup);
    else if (what == "hull3d" && p.shape[1] == 3)
      rep = verify::check_hull3d(pts(p), n, c, nc);
    else
      throw Error(ErrorCode::InvalidArgument,
                  "check: unknown structure '" + what + "' for points of this dimension");
  }
  return {rep.ok, rep.message};
}

}  // namespace

void bind_spatial(nb::module_& m) {
  using namespace nb::literals;
  m.def("delaunay2d", &delaunay2d_bind, "points"_a, "backend"_a = "auto", "stream"_a = 0,
        "threads"_a = 0, "method"_a = "incremental", "grid"_a = 0, "devices"_a = nb::none());
  nb::class_<Dynamic2dState>(m, "DynamicDelaunay2d")
      .def("__init__", &dynamic2d_init, "points"_a, "backend"_a = "auto", "stream"_a = 0,
           "threads"_a = 0)
      .def("insert", &dynamic_insert<Dynamic2dState>, "points"_a)
      .def("move", &dynamic_move<Dynamic2dState>, "points"_a)
      .def("remove", &dynamic_remove<Dynamic2dState>, "indices"_a)
      .def(
          "track_changes", [](Dynamic2dState& s, bool on) { s.t.track_changes(on); }, "on"_a)
      .def("changes", &dynamic_changes<Dynamic2dState>)
      .def("result", &dynamic2d_result)
      .def("voronoi", &dynamic_voronoi, "points"_a)
      .def_prop_ro("npoints", [](const Dynamic2dState& s) { return s.t.num_points(); });
  nb::class_<Dynamic3dState>(m, "DynamicDelaunay3d")
      .def("__init__", &dynamic3d_init, "points"_a, "backend"_a = "auto", "stream"_a = 0,
           "threads"_a = 0)
      .def("insert", &dynamic_insert<Dynamic3dState>, "points"_a)
      .def("move", &dynamic_move<Dynamic3dState>, "points"_a)
      .def("remove", &dynamic_remove<Dynamic3dState>, "indices"_a)
      .def(
          "track_changes", [](Dynamic3dState& s, bool on) { s.t.track_changes(on); }, "on"_a)
      .def("changes", &dynamic_changes<Dynamic3dState>)
      .def("result", &dynamic3d_result)
      .def("voronoi", &dynamic_voronoi3d, "points"_a)
      .def_prop_ro("npoints", [](const Dynamic3dState& s) { return s.t.num_points(); });
  m.def("voronoi2d", &voronoi2d_bind, "points"_a, "backend"_a = "auto", "stream"_a = 0,
        "threads"_a = 0);
  m.def("block_required", &block_required_bind, "simplices"_a, "neighbors"_a, "owned"_a,
        "threads"_a = 0);
  m.def("hull_candidates2d", &hull_candidates2d_bind, "points"_a, "threads"_a = 0);
  m.def("hilbert_order", &hilbert_order_bind, "points"_a);
  m.def("point_bounds", &point_bounds_bind, "points"_a, "threads"_a = 0);
  m.def("cell_counts", &cell_counts_bind, "points"_a, "lo"_a, "width"_a, "counts"_a,
        "threads"_a = 0);
  m.def("split_to_blocks", &split_to_blocks_bind, "points"_a, "lo"_a, "width"_a, "counts"_a,
        "box_lo"_a = nb::none(), "box_hi"_a = nb::none(), "box_block"_a = nb::none(),
        "wanted"_a = nb::none(), "gather"_a = false, "threads"_a = 0, "frontiers"_a = nb::none());
  m.def("empty_frontiers", &empty_frontiers_bind, "counts"_a, "lo"_a, "width"_a, "shape"_a,
        "region_lo"_a, "region_hi"_a, "cap"_a, "band"_a = 0.0, "threads"_a = 0);
  m.def("balls_in_bins", &balls_in_bins_bind, "centres"_a, "reach"_a, "lo"_a, "hi"_a, "grid_lo"_a,
        "width"_a, "counts"_a, "marked"_a, "margin"_a, "threads"_a = 0);
  m.def("block_neighbors", &block_neighbors_bind, "nb_local"_a, "offset"_a, "pos"_a, "across"_a,
        "wide"_a = false, "threads"_a = 0);
  m.def("match_faces", &match_faces_bind, "keys"_a, "positions"_a, "open"_a, "threads"_a = 0);
  m.def("block_borders", &block_borders_bind, "points"_a, "simplices"_a, "neighbors"_a, "owned"_a,
        "block"_a, "lo"_a, "width"_a, "counts"_a, "margin"_a, "scale"_a, "region_lo"_a = nb::none(),
        "region_hi"_a = nb::none(), "bounds_lo"_a = nb::none(), "bounds_hi"_a = nb::none(),
        "threads"_a = 0);
  m.def("block_output", &block_output_bind, "simplices"_a, "neighbors"_a, "rows"_a, "ids"_a,
        "blk"_a, "points"_a = nb::none(), "threads"_a = 0);
  m.def("furthest_site2d", &furthest_site2d_bind, "points"_a, "threads"_a = 0, "voronoi"_a = false);
  m.def("voronoi3d", &voronoi3d_bind, "points"_a, "backend"_a = "auto", "stream"_a = 0,
        "threads"_a = 0);
  m.def("convex_hull3d", &hull3d_bind, "points"_a, "backend"_a = "auto", "stream"_a = 0,
        "threads"_a = 0, "method"_a = "incremental", "grid"_a = 0);
  nb::class_<DynamicHullState>(m, "DynamicHull3d")
      .def("__init__", &dynamic_hull_init, "points"_a, "backend"_a = "auto", "stream"_a = 0,
           "threads"_a = 0, "method"_a = "incremental", "grid"_a = 0)
      .def("insert", &dynamic_insert<DynamicHullState>, "points"_a)
      .def("move", &dynamic_move<DynamicHullState>, "points"_a)
      .def("remove", &dynamic_remove<DynamicHullState>, "indices"_a)
      .def(
          "track_changes", [](DynamicHullState& s, bool on) { s.t.track_changes(on); }, "on"_a)
      .def("changes", &dynamic_changes<DynamicHullState>)
      .def("result", &dynamic_hull_result)
      .def_prop_ro("npoints", [](const DynamicHullState& s) { return s.t.num_points(); });
  m.def("delaunay3d", &delaunay3d_bind, "points"_a, "backend"_a = "auto", "stream"_a = 0,
        "threads"_a = 0, "progress"_a = nb::none(), "method"_a = "incremental", "grid"_a = 0,
        "devices"_a = nb::none());
  m.def("find_simplex", &find_simplex_bind, "points"_a, "simplices"_a, "neighbors"_a, "xi"_a,
        "threads"_a = 0);
  m.def("hull2d_vertices", &hull2d_bind, "points"_a, "simplices"_a, "neighbors"_a);
  m.def("circumballs_inside_region", &circumballs_inside_bind, "points"_a, "simplices"_a, "rows"_a,
        "region_lo"_a, "region_hi"_a, "bounds_lo"_a, "bounds_hi"_a, "scale"_a, "threads"_a = 0);
  m.def("check", &check_bind, "what"_a, "points"_a, "simplices"_a, "duplicate_of"_a = nb::none(),
        "segments"_a = nb::none());
  m.def("cdt2d", &cdt2d_bind, "points"_a, "segments"_a, "holes"_a, "regions"_a,
        "enclosed"_a = false, "split"_a = false, "backend"_a = "auto", "threads"_a = 0);
  m.def("cdt2d_device", &cdt2d_device_bind, "points"_a, "segments"_a, "holes"_a, "regions"_a,
        "enclosed"_a = false, "backend"_a = "auto", "stream"_a = 0, "threads"_a = 0);
}

}  // namespace gpugeom::py
