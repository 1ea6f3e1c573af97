// Bindings of quality meshing (refine2d.hpp): host points and segments in, the refined mesh's
// arrays out as a dict; or points and segments in CUDA device memory, the arrays left there.
#include <nanobind/stl/function.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <cmath>

#include "arrays.hpp"
#include "gpugeom/refine2d.hpp"
#include "verify.hpp"

namespace gpugeom::py {

namespace {

using sz = std::size_t;

// The options both entries share: holes (h, 2), regions (r, 4: x, y, attribute, max area),
// bounds, an area grid (rows, cols) with its extent (x0, y0, x1, y1), or a sizing function.
void fill_options(Refine2dOptions& o, const AnyArray& holes, const AnyArray& regions, bool enclosed,
                  double min_angle, double max_area, const nb::object& grid,
                  const nb::object& extent, std::int64_t max_steiner) {
  std::int64_t nh = 0, nr = 0;
  const double* h = reals_of(holes, "holes", 2, &nh);
  const double* g = reals_of(regions, "regions", 4, &nr);
  o.domain = enclosed ? Cdt2dOptions::Domain::Enclosed : Cdt2dOptions::Domain::ConvexHull;
  for (std::int64_t i = 0; i < nh; ++i) o.holes.push_back({h[2 * i], h[2 * i + 1]});
  for (std::int64_t i = 0; i < nr; ++i)
    o.regions.push_back({g[4 * i], g[4 * i + 1], g[4 * i + 2], g[4 * i + 3]});
  o.min_angle = min_angle;
  o.max_area = max_area;
  o.max_steiner_points = max_steiner;
  if (!grid.is_none()) {
    const Input in = inspect(nb::cast<AnyArray>(grid), "max_area grid");
    if (in.on_device || !holds<double>(in) || in.shape.size() != 2)
      throw nb::value_error("a max_area grid must be a host float64 array of shape (rows, cols)");
    const auto* v = static_cast<const double*>(in.data);
    o.area_grid.values.assign(v, v + in.shape[0] * in.shape[1]);
    o.area_grid.rows = in.shape[0];
    o.area_grid.cols = in.shape[1];
    const auto e = nb::cast<std::vector<double>>(extent);
    if (e.size() != 4) throw nb::value_error("extent must be (xmin, ymin, xmax, ymax)");
    o.area_grid.x0 = e[0], o.area_grid.y0 = e[1], o.area_grid.x1 = e[2], o.area_grid.y1 = e[3];
  }
}

nb::dict reports(nb::dict r, std::vector<std::int32_t> small, std::vector<std::int8_t> why,
                 std::vector<std::int32_t> large) {
  HostVector<std::int32_t> s(small.begin(), small.end()), l(large.begin(), large.end());
  HostVector<std::int8_t> w(why.begin(), why.end());
  const sz ns = s.size(), nl = l.size();
  r["small_angles"] = host_array(std::move(s), {ns});
  r["small_angle_reasons"] = host_array(std::move(w), {ns});
  r["large_triangles"] = host_array(std::move(l), {nl});
  return r;
}

nb::dict refine2d_bind(const AnyArray& points, const AnyArray& segments, const AnyArray& holes,
                       const AnyArray& regions, bool enclosed, bool split, double min_angle,
                       double max_area, nb::object grid, nb::object extent, nb::object sizing,
                       std::int64_t max_steiner, const std::string& backend, int threads) {
  std::int64_t n = 0, m = 0;
  const double* p = reals_of(points, "points", 2, &n);
  const std::int32_t* s = cells_of(segments, "segments", 2, &m);
  auto o = options_for<Refine2dOptions>(backend, nb::int_(0), threads, inspect(points, "points"));
  fill_options(o, holes, regions, enclosed, min_angle, max_area, grid, extent, max_steiner);
  o.crossings = split ? Cdt2dOptions::Crossings::Split : Cdt2dOptions::Crossings::Refuse;
  if (!sizing.is_none()) {
    // Called from the library's thread with the interpreter unlocked: take it for each call.
    nb::callable f = nb::cast<nb::callable>(sizing);
    o.max_area_at = [f](double x, double y) {
      nb::gil_scoped_acquire held;
      return nb::cast<double>(f(x, y));
    };
  }
  RefinedMesh2d t = unlocked([&] { return refine2d(p, n, s, m, o); });
  const sz nt = t.num_triangles, np = t.num_points;
  std::vector<std::int32_t> small(t.small_angles.begin(), t.small_angles.end()),
      large(t.large_triangles.begin(), t.large_triangles.end());
  std::vector<std::int8_t> why(t.small_angle_reasons.begin(), t.small_angle_reasons.end());
  nb::dict r;
  r["points"] = host_array(std::move(t.points), {np, 2});
  r["simplices"] = host_array(std::move(t.triangles), {nt, 3});
  r["neighbors"] = host_array(std::move(t.neighbors), {nt, 3});
  r["segment_of"] = host_array(std::move(t.segment_of), {nt, 3});
  r["duplicate_of"] = host_array(std::move(t.duplicate_of), {np});
  const sz ns = t.subsegment_of.size();
  r["subsegments"] = host_array(std::move(t.subsegments), {ns, 2});
  r["subsegment_of"] = host_array(std::move(t.subsegment_of), {ns});
  if (!t.attribute.empty()) r["attribute"] = host_array(std::move(t.attribute), {nt});
  r["num_input_points"] = t.num_input_points;
  r["removed_triangles"] = t.removed_triangles;
  r["stats"] = stats_dict(t.stats);
  return reports(r, small, why, large);
}

nb::dict refine2d_device_bind(const AnyArray& points, const AnyArray& segments,
                              const AnyArray& holes, const AnyArray& regions, bool enclosed,
                              double min_angle, double max_area, nb::object grid, nb::object extent,
                              std::int64_t max_steiner, const std::string& backend,
                              nb::handle stream, int threads) {
  const Input p = points_input(points, 2), sg = inspect(segments, "segments");
  if (!holds<std::int32_t>(sg) || sg.shape.size() != 2 || sg.shape[1] != 2)
    throw nb::value_error("segments must be an int32 array of shape (m, 2)");
  if (sg.on_device != p.on_device)
    throw nb::value_error("points and segments must be in the same memory (both on the device)");
  auto o = options_for<Refine2dOptions>(backend, stream, threads, p);
  fill_options(o, holes, regions, enclosed, min_angle, max_area, grid, extent, max_steiner);
  const std::int64_t n = p.shape[0], m = sg.shape[0];
  DeviceRefinedMesh2d t = unlocked(
      [&] { return refine2d_device(pts(p), n, static_cast<const std::int32_t*>(sg.data), m, o); });
  const DeviceOut out{t.backend, device_of(o)};
  const sz nt = sz(t.num_triangles), np = sz(t.num_points);
  nb::dict r;
  r["points"] = out(t.points, {np, 2});
  r["simplices"] = out(t.triangles, {nt, 3});
  r["neighbors"] = out(t.neighbors, {nt, 3});
  r["segment_of"] = out(t.segment_of, {nt, 3});
  r["duplicate_of"] = out(t.duplicate_of, {np});
  const sz ns = sz(t.num_subsegments);
  r["subsegments"] = out(t.subsegments, {ns, 2});
  r["subsegment_of"] = out(t.subsegment_of, {ns});
  if (t.attribute) r["attribute"] = out(t.attribute, {nt});
  r["num_input_points"] = t.num_input_points;
  r["removed_triangles"] = t.removed_triangles;
  r["stats"] = stats_dict(t.stats);
  return reports(r, std::move(t.small_angles), std::move(t.small_angle_reasons),
                 std::move(t.large_triangles));
}

// The exact checker of refined meshes (verify.hpp), on host arrays.
std::pair<bool, std::string> check_refined2d_bind(const AnyArray& points, const AnyArray& triangles,
                                                  const AnyArray& segment_of,
                                                  const AnyArray& segments,
                                                  const AnyArray& duplicate_of, double min_angle,
                                                  double max_area, const AnyArray& exempt) {
  std::int64_t n = 0, nt = 0, ng = 0, ns = 0;
  const double* p = reals_of(points, "points", 2, &n);
  const std::int32_t* t = cells_of(triangles, "triangles", 3, &nt);
  const std::int32_t* g = cells_of(segment_of, "segment_of", 3, &ng);
  const std::int32_t* s = cells_of(segments, "segments", 2, &ns);
  if (ng != nt) throw nb::value_error("segment_of must have one row per triangle");
  const Input d = inspect(duplicate_of, "duplicate_of"), e = inspect(exempt, "exempt");
  if (d.on_device || !holds<std::int32_t>(d) || d.shape.size() != 1 || d.shape[0] != n)
    throw nb::value_error("duplicate_of must be a host int32 array with one entry per point");
  if (e.on_device || !holds<std::int32_t>(e) || e.shape.size() != 1)
    throw nb::value_error("exempt must be a host int32 array of triangle indices");
  verify::Report rep;
  {
    nb::gil_scoped_release released;
    rep = verify::check_refined_mesh2d(
        p, n, t, nt, g, s, ns, static_cast<const std::int32_t*>(d.data), min_angle, max_area,
        static_cast<const std::int32_t*>(e.data), e.shape[0]);
  }
  return {rep.ok, rep.message};
}

}  // namespace

void bind_mesh(nb::module_& m) {
  using namespace nb::literals;
  m.def("refine2d", &refine2d_bind, "points"_a, "segments"_a, "holes"_a, "regions"_a,
        "enclosed"_a = true, "split"_a = false, "min_angle"_a = 20.0, "max_area"_a = 0.0,
        "grid"_a = nb::none(), "extent"_a = nb::none(), "sizing"_a = nb::none(),
        "max_steiner"_a = -1, "backend"_a = "auto", "threads"_a = 0);
  m.def("refine2d_device", &refine2d_device_bind, "points"_a, "segments"_a, "holes"_a, "regions"_a,
        "enclosed"_a = true, "min_angle"_a = 20.0, "max_area"_a = 0.0, "grid"_a = nb::none(),
        "extent"_a = nb::none(), "max_steiner"_a = -1, "backend"_a = "auto", "stream"_a = 0,
        "threads"_a = 0);
  m.def("check_refined2d", &check_refined2d_bind, "points"_a, "triangles"_a, "segment_of"_a,
        "segments"_a, "duplicate_of"_a, "min_angle"_a, "max_area"_a, "exempt"_a);
}

}  // namespace gpugeom::py
