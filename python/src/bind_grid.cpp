// Bindings of the grid capabilities: distance / feature transform and digital Voronoi labels,
// centroidal Voronoi diagrams and stippling. Grids are read where they are, in their own element
// type (the library converts on the executor); outputs go to the library's arrays or into the
// caller's (SciPy's `distances=` / `indices=`).
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <optional>

#include "arrays.hpp"
#include "gpugeom/cvd.hpp"
#include "gpugeom/edt.hpp"
#include "gpugeom/multi_gpu.hpp"

namespace gpugeom::py {

namespace {

using sz = std::size_t;
using OutArray = nb::ndarray<>;  // writable, any kind

io::ScalarType scalar_of(const Input& in, const char* name) {
  if (in.dtype == nb::dtype<bool>()) return io::ScalarType::Bool;
  if (holds<std::uint8_t>(in)) return io::ScalarType::U8;
  if (holds<std::uint16_t>(in)) return io::ScalarType::U16;
  if (holds<std::int32_t>(in)) return io::ScalarType::I32;
  if (holds<std::int64_t>(in)) return io::ScalarType::I64;
  if (holds<float>(in)) return io::ScalarType::F32;
  if (holds<double>(in)) return io::ScalarType::F64;
  throw nb::type_error((std::string(name) +
                        ": element type not read directly (bool, uint8, uint16, int32, int64, "
                        "float32, float64 are)")
                           .c_str());
}

GridView view(const Input& in) {
  return GridView{in.data, scalar_of(in, "input"), in.shape};
}

std::vector<sz> dims(const std::vector<std::int64_t>& shape, std::int64_t lead = 0) {
  std::vector<sz> d;
  if (lead) d.push_back(sz(lead));
  for (auto e : shape) d.push_back(sz(e));
  return d;
}

// A caller's output array: where the input is, C order, the given element type and count.
template <class T>
OutBuffer<T> out_buffer(const std::optional<OutArray>& a, const Input& grid, const char* name,
                        const char* type) {
  if (!a) return {};
  AnyArray ro(*a);
  Input o = inspect(ro, name);
  if (o.on_device != grid.on_device)
    throw nb::value_error((std::string(name) + " must be in the same memory as the input (" +
                           (grid.on_device ? "GPU" : "host") + ")")
                              .c_str());
  if (!holds<T>(o)) throw nb::type_error((std::string(name) + " must be " + type).c_str());
  std::int64_t count = 1;
  for (auto e : o.shape) count *= e;
  return OutBuffer<T>{static_cast<T*>(a->data()), count};
}

// A slab's bound per column (EdtSlab): a host int64 array.
std::vector<std::int64_t> column_bound(const std::optional<AnyArray>& a, const char* name) {
  if (!a) throw nb::value_error((std::string(name) + " is needed with slab_extent").c_str());
  const Input b = inspect(*a, name);
  if (b.on_device || !holds<std::int64_t>(b))
    throw nb::type_error((std::string(name) + " must be a host int64 array").c_str());
  std::int64_t c = 1;
  for (auto e : b.shape) c *= e;
  const auto* p = static_cast<const std::int64_t*>(b.data);
  return std::vector<std::int64_t>(p, p + c);
}

nb::dict edt_bind(const AnyArray& input, bool zero_sites, std::vector<double> sampling,
                  int distance, bool squared, bool features, bool labels,
                  std::optional<OutArray> distances_out, std::optional<OutArray> features_out,
                  const std::string& backend, nb::handle stream, int threads,
                  std::vector<std::int64_t> slices, std::int64_t slab_extent,
                  std::int64_t slab_first, std::optional<AnyArray> slab_before,
                  std::optional<AnyArray> slab_after, std::optional<std::vector<int>> devices) {
  const Input in = inspect(input, "input");
  if (in.shape.size() < 2 || in.shape.size() > 8)
    throw nb::value_error("input must have 2 to 8 dimensions");
  auto o = options_for<EdtOptions>(backend, stream, threads, in);
  o.slices = std::move(slices);
  if (slab_extent) {
    o.slab.extent = slab_extent;
    o.slab.first = slab_first;
    o.slab.before = column_bound(slab_before, "slab_before");
    o.slab.after = column_bound(slab_after, "slab_after");
  }
  o.sampling = std::move(sampling);
  o.distance = distance;
  o.squared = squared;
  o.features = features;
  o.labels = labels;
  if (distance == 64)
    o.into.distance64 = out_buffer<double>(distances_out, in, "distances", "float64");
  if (distance == 32)
    o.into.distance32 = out_buffer<float>(distances_out, in, "distances", "float32");
  if (distances_out && distance == 0)
    throw nb::value_error("distances= given but no distances asked for");
  o.into.features = out_buffer<std::int32_t>(features_out, in, "indices", "int32");
  const SiteRule rule = zero_sites ? SiteRule::Zero : SiteRule::NonZero;
  const int nd = int(in.shape.size());
  nb::dict r;
  if (in.on_device) {
    if (devices) throw nb::value_error("devices= reads host arrays (each device takes its slab)");
    const DeviceEdtResult e =
        unlocked([&] { return distance_transform_device(view(in), rule, o); });
    const DeviceOut out{e.backend, device_of(o)};
    if (e.distance64) r["distances"] = out(e.distance64, dims(e.shape));
    if (e.distance32) r["distances"] = out(e.distance32, dims(e.shape));
    if (e.sqdist_int) r["sqdist"] = out(e.sqdist_int, dims(e.shape));
    if (e.sqdist_real) r["sqdist"] = out(e.sqdist_real, dims(e.shape));
    if (e.features) r["indices"] = out(e.features, dims(e.shape, nd));
    if (e.labels) r["labels"] = out(e.labels, dims(e.shape));
    r["stats"] = stats_dict(e.stats);
    return r;
  }
  EdtResult e = unlocked([&] {
    return devices ? distance_transform_devices(view(in), rule, *devices, o)
                   : distance_transform(view(in), rule, o);
  });
  if (!e.distance64.empty()) r["distances"] = host_array(std::move(e.distance64), dims(e.shape));
  if (!e.distance32.empty()) r["distances"] = host_array(std::move(e.distance32), dims(e.shape));
  if (!e.sqdist_int.empty()) r["sqdist"] = host_array(std::move(e.sqdist_int), dims(e.shape));
  if (!e.sqdist_real.empty()) r["sqdist"] = host_array(std::move(e.sqdist_real), dims(e.shape));
  if (!e.features.empty()) r["indices"] = host_array(std::move(e.features), dims(e.shape, nd));
  if (!e.labels.empty()) r["labels"] = host_array(std::move(e.labels), dims(e.shape));
  r["stats"] = stats_dict(e.stats);
  return r;
}

// Per column, the first and last site along axis 0 (a slab's bounds for its neighbours).
nb::tuple column_bounds_bind(const AnyArray& input, bool zero_sites, std::int64_t offset,
                             int threads, nb::handle stream) {
  const Input in = inspect(input, "input");
  const RunOptions run = run_options("auto", stream, threads, in);
  const SiteRule rule = zero_sites ? SiteRule::Zero : SiteRule::NonZero;
  ColumnSiteBounds b = unlocked([&] {
    return in.on_device ? column_site_bounds_device(view(in), rule, offset, run)
                        : column_site_bounds(view(in), rule, offset, run);
  });
  const sz cols = b.first.size();
  return nb::make_tuple(host_array(std::move(b.first), {cols}),
                        host_array(std::move(b.last), {cols}), b.columns_with_sites);
}

// The Lloyd options shared by cvd and stipple; the callback runs with the interpreter locked and
// lets Ctrl-C end the run (a borrowed handle: the caller holds it for the whole call).
void lloyd_options(CvdOptions& o, std::int64_t num_sites, std::optional<AnyArray> initial,
                   int max_iterations, double move_tolerance, double energy_tolerance,
                   int supersample, std::uint64_t seed, nb::object progress) {
  o.num_sites = num_sites;
  if (initial) {
    Input s = inspect(*initial, "initial_sites");
    if (s.on_device || !holds<double>(s))
      throw nb::type_error("initial_sites must be a host float64 array");
    std::int64_t c = 1;
    for (auto e : s.shape) c *= e;
    const double* p = static_cast<const double*>(s.data);
    o.initial_sites.assign(p, p + c);
  }
  o.max_iterations = max_iterations;
  o.move_tolerance = move_tolerance;
  o.energy_tolerance = energy_tolerance;
  o.supersample = supersample;
  o.seed = seed;
  PyObject* cb = progress.is_none() ? nullptr : progress.ptr();
  o.progress = [cb](const CvdProgress& p) {
    nb::gil_scoped_acquire locked;
    if (PyErr_CheckSignals() != 0) throw nb::python_error();
    if (!cb) return true;
    nb::handle f(cb);
    nb::object r = f(p.iteration, p.energy, p.max_move, p.moved);
    return r.is_none() || nb::cast<bool>(r);
  };
}

void put_cvd_host(nb::dict& r, CvdResult& c) {
  const sz k = sz(c.num_sites), it = c.energy.size();
  r["sites"] = host_array(std::move(c.sites), {k, sz(c.dim)});
  r["mass"] = host_array(std::move(c.mass), {k});
  r["energy"] = host_array(std::move(c.energy), {it});
  r["iterations"] = c.iterations;
  r["converged"] = c.converged;
  r["stats"] = stats_dict(c.stats);
}

nb::dict cvd_bind(const AnyArray& density, std::int64_t num_sites, std::optional<AnyArray> initial,
                  int max_iterations, double move_tolerance, double energy_tolerance,
                  int supersample, std::uint64_t seed, nb::object progress,
                  const std::string& backend, nb::handle stream, int threads) {
  const Input in = inspect(density, "density");
  auto o = options_for<CvdOptions>(backend, stream, threads, in);
  lloyd_options(o, num_sites, initial, max_iterations, move_tolerance, energy_tolerance,
                supersample, seed, progress);
  nb::dict r;
  if (in.on_device) {
    DeviceCvdResult c = unlocked([&] { return centroidal_voronoi_device(view(in), o); });
    const DeviceOut out{c.backend, device_of(o)};
    const sz k = sz(c.num_sites), it = c.energy.size();
    r["sites"] = out(c.sites, {k, sz(c.dim)});
    r["mass"] = out(c.mass, {k});
    r["energy"] = host_array(std::move(c.energy), {it});
    r["iterations"] = c.iterations;
    r["converged"] = c.converged;
    r["stats"] = stats_dict(c.stats);
    return r;
  }
  CvdResult c = unlocked([&] { return centroidal_voronoi(view(in), o); });
  put_cvd_host(r, c);
  return r;
}

nb::dict stipple_bind(const AnyArray& image, std::int64_t num_sites, bool invert, double contrast,
                      double gamma, double ink, int max_iterations, double move_tolerance,
                      double energy_tolerance, int supersample, std::uint64_t seed,
                      nb::object progress, const std::string& backend, int threads) {
  const Input in = inspect(image, "image");
  if (in.on_device) throw nb::value_error("stipple reads the image from host memory");
  auto o = options_for<StippleOptions>(backend, nb::int_(0), threads, in);
  lloyd_options(o, num_sites, std::nullopt, max_iterations, move_tolerance, energy_tolerance,
                supersample, seed, progress);
  o.invert = invert;
  o.contrast = contrast;
  o.gamma = gamma;
  o.ink = ink;
  Stipple s = unlocked([&] { return stipple(view(in), o); });
  nb::dict r;
  const sz k = sz(s.cvd.num_sites);
  r["radius"] = host_array(std::move(s.radius), {k});
  put_cvd_host(r, s.cvd);
  return r;
}

}  // namespace

void bind_grid(nb::module_& m) {
  using namespace nb::literals;
  m.def("distance_transform", &edt_bind, "input"_a, "zero_sites"_a, "sampling"_a, "distance"_a,
        "squared"_a, "features"_a, "labels"_a, "distances_out"_a = nb::none(),
        "features_out"_a = nb::none(), "backend"_a = "auto", "stream"_a = 0, "threads"_a = 0,
        "slices"_a = std::vector<std::int64_t>{}, "slab_extent"_a = 0, "slab_first"_a = 0,
        "slab_before"_a = nb::none(), "slab_after"_a = nb::none(), "devices"_a = nb::none());
  m.def("column_site_bounds", &column_bounds_bind, "input"_a, "zero_sites"_a, "offset"_a = 0,
        "threads"_a = 0, "stream"_a = 0);
  m.def("centroidal_voronoi", &cvd_bind, "density"_a, "num_sites"_a, "initial_sites"_a = nb::none(),
        "max_iterations"_a = 200, "move_tolerance"_a = 0.1, "energy_tolerance"_a = 0.0,
        "supersample"_a = 1, "seed"_a = 1, "progress"_a = nb::none(), "backend"_a = "auto",
        "stream"_a = 0, "threads"_a = 0);
  m.def("stipple", &stipple_bind, "image"_a, "num_sites"_a, "invert"_a = false, "contrast"_a = 1.0,
        "gamma"_a = 1.0, "ink"_a = 0.6, "max_iterations"_a = 200, "move_tolerance"_a = 0.1,
        "energy_tolerance"_a = 0.0, "supersample"_a = 1, "seed"_a = 1, "progress"_a = nb::none(),
        "backend"_a = "auto", "threads"_a = 0);
}

}  // namespace gpugeom::py
