// Public entry of the distance transform: checks the request, packs the sites, picks the
// backend, and returns outputs in C axis order.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>

#include "base/stats_fields.hpp"
#include "edt/edt_backend.hpp"
#include "edt/entries.hpp"
#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "exec/grid_input.hpp"
#include "base/hd.hpp"
#include "gpugeom/edt.hpp"

namespace gpugeom {

// clang-format off
#define GG_EDT_COUNTERS(X) X(bands_x) X(bands_y) X(bands_z) X(slices_per_block) X(index_bits) X(slabs)
// clang-format on
GG_COUNTER_MAP(EdtStats, GG_EDT_COUNTERS);
#undef GG_EDT_COUNTERS

std::int64_t EdtResult::count() const {
  std::int64_t n = 1;
  for (auto s : shape) n *= s;
  return shape.empty() ? 0 : n;
}

namespace edt {

namespace {
int bits_for(std::int64_t n) {
  int b = 0;
  while ((std::int64_t(1) << b) < n) ++b;
  return b;
}
}  // namespace

// sliced: only slices of nx * ny voxels are held at once, so only they must fit int32 indexing
// (the slices' own site packing, SliceLayout, needs no more).
Layout make_layout(const std::vector<std::int64_t>& shape, bool sliced, Packing packing,
                   const detail::Tuning& tuning) {
  if (shape.size() != 2 && shape.size() != 3)
    throw Error(ErrorCode::InvalidInput, "these grids must be 2D or 3D, got " +
                                             std::to_string(shape.size()) + " dimensions");
  Layout L;
  L.nd = int(shape.size());
  for (int a = 0; a < L.nd; ++a) {
    const std::int64_t e = shape[L.nd - 1 - a];  // internal axis a = C axis nd-1-a
    if (e <= 0) throw Error(ErrorCode::InvalidInput, "grid extents must be positive");
    // The GPU passes decide in doubles (pba.inl, cand_dominated): exact while its three terms,
    // each below extent^3 in 2D and 2 extent^3 in 3D, sum below 2^53.
    const std::int64_t most = L.nd == 2 ? 131072 : 65536;
    if (e > most)
      throw Error(ErrorCode::InvalidInput, "grid extent " + std::to_string(e) +
                                               " too large: at most " + std::to_string(most) +
                                               " along an axis of a " + std::to_string(L.nd) +
                                               "D grid");
    L.n[a] = e;
  }
  int shift = 0;
  for (int a = 0; a < 3; ++a) {
    const int b = bits_for(L.n[a]);
    L.shift[a] = shift;
    L.mask[a] = b ? std::uint32_t((std::uint64_t(1) << b) - 1) : 0;
    shift += b;
  }
  // Bit fields where they fit 32 bits (the faster decode), else raster indices, which hold
  // every grid of fewer than 2^32 - 1 voxels (kNone is the last 32-bit value); by slices, past
  // that, sites packed by column (ColumnLayout), where only a slice must fit.
  const std::int64_t n = L.count();
  if (sliced) {
    if (L.n[0] * L.n[1] >= (std::int64_t(1) << 31) - 1)
      throw Error(ErrorCode::InvalidInput,
                  "a slice of " + std::to_string(L.n[0] * L.n[1]) +
                      " voxels is too large: at most 2^31-2 (e.g. 46340 x 46340)");
    if (n >= (std::int64_t(1) << 32) - 1 || tuning.edt.column_packing) {
      L.columns = true;
      return L;
    }
  }
  if (n >= (std::int64_t(1) << 32) - 1)
    throw Error(ErrorCode::InvalidInput,
                "grid too large for a whole transform: " + std::to_string(n) +
                    " voxels, at most 2^32-2 (4294967294; e.g. 1625^3, 2048 x 2048 x 1023); "
                    "compute it by slices (EdtOptions::slices), which takes any number");
  if (shift > 32 || (tuning.edt.linear_packing && packing == Packing::Any)) {
    if (packing == Packing::Bits)
      throw Error(ErrorCode::InvalidInput,
                  "grid extents too large: the coordinates of a grid point must fit 32 bits "
                  "together (e.g. 1024 x 1024 x 2048, 32768 x 65536), these need " +
                      std::to_string(shift));
    L.linear = true;
  }
  return L;
}

}  // namespace edt

namespace {

template <int D>
edt::MetricT<D> make_metric(const std::vector<double>& sampling, int nd) {
  edt::MetricT<D> m;
  if (sampling.empty()) return m;
  if (int(sampling.size()) != nd)
    throw Error(ErrorCode::InvalidArgument, "sampling needs one value per axis (" +
                                                std::to_string(nd) + "), got " +
                                                std::to_string(sampling.size()));
  for (int j = 0; j < nd; ++j) {
    const double s = sampling[j];
    if (!(s > 0) || !std::isfinite(s) || !(s * s > 1e-150) || !(s * s < 1e150))
      throw Error(ErrorCode::InvalidArgument,
                  "sampling values must be positive and finite (and in 1e-75..1e75)");
    const int a = nd - 1 - j;
    double hi, lo;
    exact::two_product(s, s, hi, lo);
    m.wh[a] = hi, m.wl[a] = lo, m.w[a] = hi;
    if (s != 1.0) m.iso = false;
  }
  return m;
}

// The shape of a grid of 4 to 8 axes, checked. Its passes decide in doubles on the GPU (exact
// below 2^53: the largest term, 2 n_a F + n_a^3 with F the squared diagonal, is bounded here)
// and index sites by 32 bits where the grid has fewer than 2^32 - 1 voxels, else by 64.
edt::NdShape make_nd_shape(const std::vector<std::int64_t>& shape, bool wide) {
  const int nd = int(shape.size());
  if (nd < 4 || nd > edt::kMaxAxes)
    throw Error(ErrorCode::InvalidInput, "the distance transform takes grids of 2 to " +
                                             std::to_string(edt::kMaxAxes) + " axes, got " +
                                             std::to_string(nd));
  edt::NdShape g;
  g.nd = nd;
  double diag = 0, most = 0, count = 1;
  for (int a = 0; a < nd; ++a) {
    const std::int64_t e = shape[nd - 1 - a];
    if (e <= 0) throw Error(ErrorCode::InvalidInput, "grid extents must be positive");
    if (e > 65536)
      throw Error(ErrorCode::InvalidInput,
                  "grid extent " + std::to_string(e) + " too large: at most 65536 along an axis");
    g.n[a] = e;
    diag += double(e) * double(e);
    most = std::max(most, double(e));
    count *= double(e);
  }
  if (2 * most * diag + most * most * most >= 9007199254740992.0)
    throw Error(ErrorCode::InvalidInput,
                "grid extents too large for the exact passes of a " + std::to_string(nd) +
                    "D grid: 2 n (sum of n_k^2) + n^3 must stay below 2^53 for the longest axis n");
  if (count >= 9.2e18) throw Error(ErrorCode::InvalidInput, "grid too large");
  if (count / double(g.n[nd - 1]) >= 140737488355328.0)  // column keys hold 47 bits
    throw Error(ErrorCode::InvalidInput,
                "grid too large: a slice along axis 0 must hold fewer "
                "than 2^47 elements");
  g.wide = wide || g.count() >= (std::int64_t(1) << 32) - 1;
  return g;
}

// The grid's shape and metric in the request: a 2D / 3D layout, or an N-D shape.
void set_grid(edt::Request& rq, const std::vector<std::int64_t>& shape, const EdtOptions& opt) {
  if (shape.size() < 2 || shape.size() > std::size_t(edt::kMaxAxes))
    throw Error(ErrorCode::InvalidInput, "the distance transform takes grids of 2 to " +
                                             std::to_string(edt::kMaxAxes) + " axes, got " +
                                             std::to_string(shape.size()));
  if (shape.size() >= 4) {
    rq.nd = make_nd_shape(shape, opt.wide_indices);
    rq.nd_metric = make_metric<edt::kMaxAxes>(opt.sampling, rq.nd.nd);
    if (opt.method != EdtMethod::Pba)
      throw Error(ErrorCode::InvalidArgument, "grids of 4 or more axes take the PBA method only");
    return;
  }
  rq.layout =
      edt::make_layout(shape, !opt.slices.empty(), edt::Packing::Any, detail::tuning_of(opt));
  rq.metric = make_metric<3>(opt.sampling, rq.layout.nd);
}

// The request's output choices from the options; the caller's arrays checked against the
// output size (`total` voxels of `nd` axes).
void set_outputs(edt::Request& rq, const EdtOptions& opt, std::int64_t total, int nd) {
  if (opt.distance != 0 && opt.distance != 32 && opt.distance != 64)
    throw Error(ErrorCode::InvalidArgument, "distance must be 0, 32 or 64 (bits)");
  rq.want_sqdist = opt.squared;
  rq.want_distance = opt.distance;
  rq.want_features = opt.features;
  rq.want_labels = opt.labels;
  rq.into = opt.into;
  auto check = [&](const auto& b, bool asked, const char* name, const char* ask,
                   std::int64_t need) {
    if (!b) return;
    if (!asked)
      throw Error(ErrorCode::InvalidArgument, std::string("an array for the ") + name +
                                                  " was given (into." + name + "), but " + ask);
    if (b.size != need)
      throw Error(ErrorCode::InvalidArgument,
                  std::string("into.") + name + " holds " + std::to_string(b.size) +
                      " elements; this output needs " + std::to_string(need));
  };
  // (grids of 4 to 8 axes keep their metric in nd_metric)
  const bool iso = rq.nd.nd ? rq.nd_metric.iso : rq.metric.iso;
  check(opt.into.sqdist_int, opt.squared && iso, "sqdist_int",
        "squared isotropic distances were not asked for (squared, no sampling other than 1)",
        total);
  check(opt.into.sqdist_real, opt.squared && !iso, "sqdist_real",
        "squared anisotropic distances were not asked for (squared, with sampling)", total);
  check(opt.into.distance32, opt.distance == 32, "distance32", "distance is not 32", total);
  check(opt.into.distance64, opt.distance == 64, "distance64", "distance is not 64", total);
  check(opt.into.features, opt.features, "features", "features is false", total * nd);
  check(opt.into.labels, opt.labels, "labels", "labels is false", total);
}

}  // namespace

namespace edt {
bool checked_outputs(const std::vector<std::int64_t>& shape, const EdtOptions& opt) {
  Request rq;
  EdtOptions o = opt;
  o.slices = {0};  // (the sliced packing: a whole grid's size limit is not this check's)
  set_grid(rq, shape, o);
  std::int64_t total = 1;
  for (auto e : shape) total *= e;
  set_outputs(rq, opt, total, int(shape.size()));
  return rq.nd.nd ? rq.nd_metric.iso : rq.metric.iso;
}
}  // namespace edt

namespace {

// Checks the slices and returns the output shape.
std::vector<std::int64_t> output_shape(edt::Request& rq, const EdtOptions& opt,
                                       const std::vector<std::int64_t>& shape) {
  std::vector<std::int64_t> out = shape;
  if (!opt.slices.empty()) {
    if (shape.size() < 3)
      throw Error(ErrorCode::InvalidArgument, "slices apply to grids of 3 or more axes only");
    if (opt.method != EdtMethod::Pba)
      throw Error(ErrorCode::InvalidArgument, "slices need the PBA method");
    for (auto z : opt.slices)
      if (z < 0 || z >= shape[0])
        throw Error(ErrorCode::InvalidArgument, "slice " + std::to_string(z) + " is outside 0.." +
                                                    std::to_string(shape[0] - 1));
    rq.slices = opt.slices;
    out[0] = std::int64_t(opt.slices.size());
  }
  return out;
}

void prepare(edt::Request& rq, const EdtOptions& opt, const std::vector<std::int64_t>& shape,
             std::vector<std::int64_t>& out_shape) {
  rq.method = opt.method;
  for (int a = 0; a < 3; ++a) rq.tune.bands[a] = opt.bands[a];
  rq.tune.window_reach = opt.window_reach;
  rq.tune.tiles = opt.tiles;
  if (opt.slice_block < 0)
    throw Error(ErrorCode::InvalidArgument, "slice_block must be 0 (automatic) or positive");
  rq.tune.slice_block = opt.slice_block;
  rq.run = static_cast<const RunOptions&>(opt);
  out_shape = output_shape(rq, opt, shape);
  std::int64_t total = 1;
  for (auto e : out_shape) total *= e;
  set_outputs(rq, opt, total, int(shape.size()));
}

void run_backend(Backend b, const edt::Request& rq, edt::Output& out, EdtStats& stats) {
  stats.backend = b;
  GG_ENTRIES(b, edt).run(rq, out, stats);
}

// The result's six arrays from the backend's (host or device) arrays of the same names.
template <class R, class A, class B, class C, class D, class E>
void take_arrays(R& r, A& sqdist_int, B& sqdist_real, C& dist32, D& dist64, E& features,
                 E& labels) {
  r.sqdist_int = std::move(sqdist_int);
  r.sqdist_real = std::move(sqdist_real);
  r.distance32 = std::move(dist32);
  r.distance64 = std::move(dist64);
  r.features = std::move(features);
  r.labels = std::move(labels);
}

EdtResult finish(edt::Request& rq, const EdtOptions& opt, const std::vector<std::int64_t>& shape) {
  EdtResult r;
  prepare(rq, opt, shape, r.shape);
  edt::Output out;
  run_backend(resolve_backend(opt.backend, opt.device), rq, out, r.stats);
  take_arrays(r, out.sqdist_int, out.sqdist_real, out.dist32, out.dist64, out.features, out.labels);
  return r;
}

// The sites of a host grid of n voxels (slices of `plane` voxels along C axis 0) as column keys,
// in raster order, on all host threads: each chunk
// counts its sites, then writes them at its offset. Elements are read as their own type (a
// conversion to double per element took 3.7 ns an element a thread). False if a NaN is met.
template <class T>
bool list_column_sites(const T* data, std::int64_t n, std::int64_t plane, bool nonzero,
                       std::vector<std::uint64_t>& out, int threads, std::int64_t z0 = 0) {
  if (threads <= 0) threads = omp_get_max_threads();
  constexpr std::int64_t kChunk = std::int64_t(1) << 20;
  const std::int64_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<std::int64_t> at(std::size_t(chunks) + 1, 0);
  bool finite = true;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) reduction(&& : finite)
  for (std::int64_t c = 0; c < chunks; ++c) {
    std::int64_t k = 0;
    bool nan = false;
    for (std::int64_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) {
      const T v = data[i];
      if constexpr (std::is_floating_point_v<T>) nan |= v != v;
      k += nonzero ? v != T(0) : v == T(0);
    }
    at[std::size_t(c) + 1] = k;
    finite = finite && !nan;
  }
  if (!finite) return false;
  for (std::int64_t c = 0; c < chunks; ++c) at[std::size_t(c) + 1] += at[std::size_t(c)];
  out.resize(std::size_t(at.back()));
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::int64_t c = 0; c < chunks; ++c) {
    std::int64_t k = at[std::size_t(c)];
    for (std::int64_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i)
      if (nonzero ? data[i] != T(0) : data[i] == T(0))
        out[std::size_t(k++)] = edt::column_key(i % plane, i / plane + z0);
  }
  return true;
}

void check_view(const GridView& g) {
  if (!g.data) throw Error(ErrorCode::InvalidArgument, "the grid's data pointer is null");
}

// A slab (EdtOptions::slab) of a grid of `shape`, checked: returns the whole grid's shape, with
// `o` the options for it (the slab's indices as slices, no slab) and the slab's bounds appended
// to `keys` as column keys.
std::vector<std::int64_t> slab_setup(const std::vector<std::int64_t>& shape, const EdtOptions& opt,
                                     EdtOptions& o, std::vector<std::uint64_t>& keys) {
  const EdtSlab& s = opt.slab;
  if (shape.size() < 3)
    throw Error(ErrorCode::InvalidArgument,
                "a slab (EdtOptions::slab) takes grids of 3 to 8 axes: give a 2D grid as (rows, 1, "
                "columns)");
  if (!opt.slices.empty())
    throw Error(ErrorCode::InvalidArgument,
                "a slab computes all its indices along axis 0: slices cannot be given with it");
  if (opt.labels)
    throw Error(ErrorCode::InvalidArgument,
                "a slab gives no labels (a site's rank in the whole grid is not known to it): ask "
                "for features instead");
  const std::int64_t n0 = shape[0];
  if (s.first < 0 || s.first + n0 > s.extent)
    throw Error(ErrorCode::InvalidArgument,
                "the slab's indices along axis 0, " + std::to_string(s.first) + ".." +
                    std::to_string(s.first + n0 - 1) + ", must lie in the whole grid's 0.." +
                    std::to_string(s.extent - 1));
  std::int64_t plane = 1;
  for (std::size_t a = 1; a < shape.size(); ++a) plane *= shape[a];
  if (std::int64_t(s.before.size()) != plane || std::int64_t(s.after.size()) != plane)
    throw Error(ErrorCode::InvalidArgument,
                "slab.before and slab.after need one value per column (" + std::to_string(plane) +
                    "), got " + std::to_string(s.before.size()) + " and " +
                    std::to_string(s.after.size()));
  const std::int64_t end = s.first + n0;
  for (std::int64_t c = 0; c < plane; ++c) {
    const std::int64_t b = s.before[std::size_t(c)], a = s.after[std::size_t(c)];
    if (b != -1 && (b < 0 || b >= s.first))
      throw Error(ErrorCode::InvalidArgument,
                  "slab.before[" + std::to_string(c) + "] = " + std::to_string(b) +
                      " is neither -1 nor an index before the slab (0.." +
                      std::to_string(s.first - 1) + ")");
    if (a != -1 && (a < end || a >= s.extent))
      throw Error(ErrorCode::InvalidArgument,
                  "slab.after[" + std::to_string(c) + "] = " + std::to_string(a) +
                      " is neither -1 nor an index after the slab (" + std::to_string(end) + ".." +
                      std::to_string(s.extent - 1) + ")");
    if (b >= 0) keys.push_back(edt::column_key(c, b));
    if (a >= 0) keys.push_back(edt::column_key(c, a));
  }
  o = opt;
  o.slab = {};
  o.slices.resize(std::size_t(n0));
  for (std::int64_t z = 0; z < n0; ++z) o.slices[std::size_t(z)] = s.first + z;
  std::vector<std::int64_t> whole = shape;
  whole[0] = s.extent;
  return whole;
}

// A host slab: the slice-by-slice mode on the whole grid's shape, computing the slab's indices,
// from the slab's sites (their axis-0 index moved by `first`) and its bounds, listed here.
EdtResult slab_transform(const GridView& g, SiteRule rule, const EdtOptions& opt) {
  EdtOptions o;
  std::vector<std::uint64_t> bounds;
  const std::vector<std::int64_t> whole = slab_setup(g.shape, opt, o, bounds);
  edt::Request rq;
  set_grid(rq, whole, o);
  std::int64_t n = 1;
  for (auto e : g.shape) n *= e;
  bool finite = true;
  grid_input::visit(g.type, [&](auto tag) {
    finite =
        list_column_sites(static_cast<const decltype(tag)*>(g.data), n, n / g.shape[0],
                          rule == SiteRule::NonZero, rq.column_sites, opt.threads, opt.slab.first);
  });
  if (!finite) throw Error(ErrorCode::InvalidInput, "the grid contains NaN values");
  rq.column_sites.insert(rq.column_sites.end(), bounds.begin(), bounds.end());
  if (rq.column_sites.empty())
    throw Error(ErrorCode::InvalidInput,
                std::string("neither the slab nor its bounds hold a site (no ") +
                    (rule == SiteRule::NonZero ? "nonzero" : "zero") +
                    " element): every distance would be infinite");
  rq.site_count = std::int64_t(rq.column_sites.size());
  return finish(rq, o, whole);
}

void refuse_slab(const EdtOptions& opt, const char* entry) {
  if (opt.slab.extent)
    throw Error(ErrorCode::InvalidArgument,
                std::string(entry) +
                    " takes no slab (EdtOptions::slab): a slab is a grid, given to "
                    "distance_transform or distance_transform_device");
}

}  // namespace

EdtResult distance_transform(const GridView& g, SiteRule rule, const EdtOptions& opt) {
  check_view(g);
  if (opt.slab.extent) return slab_transform(g, rule, opt);
  edt::Request rq;
  set_grid(rq, g.shape, opt);
  if (opt.slices.empty()) {  // the executor reads the grid as it is
    rq.grid = g.data;
    rq.type = g.type;
    rq.rule = rule;
    return finish(rq, opt, g.shape);
  }
  // Slice by slice: the device holds the site list and a block of slices, never the volume, so
  // the sites are listed here as column keys (raster order: labels are raster ranks as usual).
  bool finite = true;
  std::int64_t n = 1;
  for (auto e : g.shape) n *= e;
  const std::int64_t plane = n / g.shape[0];
  grid_input::visit(g.type, [&](auto tag) {
    finite = list_column_sites(static_cast<const decltype(tag)*>(g.data), n, plane,
                               rule == SiteRule::NonZero, rq.column_sites, opt.threads);
  });
  if (!finite) throw Error(ErrorCode::InvalidInput, "the grid contains NaN values");
  if (rq.column_sites.empty())
    throw Error(ErrorCode::InvalidInput, std::string("the grid has no site (no ") +
                                             (rule == SiteRule::NonZero ? "nonzero" : "zero") +
                                             " element): every distance would be infinite");
  rq.site_count = std::int64_t(rq.column_sites.size());
  return finish(rq, opt, g.shape);
}

std::int64_t DeviceEdtResult::count() const {
  std::int64_t n = 1;
  for (auto s : shape) n *= s;
  return shape.empty() ? 0 : n;
}

DeviceEdtResult distance_transform_device(const GridView& g, SiteRule rule, const EdtOptions& opt) {
  check_view(g);
  const Backend b = device_entry_backend(opt.backend, opt.device, "distance_transform_device");
  edt::Request rq;
  // A slab (EdtOptions::slab): the slices of the whole grid's shape that the slab holds, its
  // sites listed on the device with its bounds.
  EdtOptions so;
  std::vector<std::int64_t> shape = g.shape;
  if (opt.slab.extent) {
    shape = slab_setup(g.shape, opt, so, rq.column_sites);
    rq.slab_first = opt.slab.first;
    rq.slab_planes = g.shape[0];
  }
  const EdtOptions& o = opt.slab.extent ? so : opt;
  set_grid(rq, shape, o);
  rq.grid = g.data;
  rq.type = g.type;
  rq.rule = rule;
  rq.grid_on_device = true;
  rq.device_out = true;
  DeviceEdtResult r;
  r.backend = b;
  prepare(rq, o, shape, r.shape);
  edt::Output out;
  run_backend(b, rq, out, r.stats);
  take_arrays(r, out.dev_sqdist_int, out.dev_sqdist_real, out.dev_dist32, out.dev_dist64,
              out.dev_features, out.dev_labels);
  return r;
}

EdtResult distance_transform_sites(const std::vector<std::int64_t>& shape,
                                   const std::vector<std::int64_t>& sites, const EdtOptions& opt) {
  refuse_slab(opt, "distance_transform_sites");
  edt::Request rq;
  set_grid(rq, shape, opt);
  const int nd = int(shape.size());
  if (sites.empty() || sites.size() % nd)
    throw Error(ErrorCode::InvalidInput,
                sites.empty() ? "no sites given: every distance would be infinite"
                              : "the site list is not a whole number of coordinates");
  const std::int64_t ns = std::int64_t(sites.size()) / nd;
  if (ns >= (std::int64_t(1) << 31))
    throw Error(ErrorCode::InvalidInput, "too many sites (at most 2^31-1)");
  const bool sliced = !opt.slices.empty();
  if (rq.nd.nd && !sliced)
    rq.nd_sites.resize(std::size_t(ns));
  else if (sliced)
    rq.column_sites.resize(std::size_t(ns));
  else
    rq.sites.resize(std::size_t(ns));
  rq.site_count = ns;
  for (std::int64_t i = 0; i < ns; ++i) {
    std::int64_t c[3] = {0, 0, 0};
    std::uint64_t raster = 0;
    for (int j = 0; j < nd; ++j) {
      const std::int64_t v = sites[i * nd + j];
      if (v < 0 || v >= shape[j])
        throw Error(ErrorCode::InvalidInput,
                    "site " + std::to_string(i) + " lies outside the grid (coordinate " +
                        std::to_string(v) + " on axis " + std::to_string(j) + ")");
      raster = raster * std::uint64_t(shape[j]) + std::uint64_t(v);
      if (nd <= 3) c[nd - 1 - j] = v;
    }
    const std::uint64_t plane = std::uint64_t(rq.nd.nd ? rq.nd.count() / shape[0] : 0);
    if (rq.nd.nd && sliced)
      rq.column_sites[i] = edt::column_key(std::int64_t(raster % plane), sites[i * nd]);
    else if (rq.nd.nd)
      rq.nd_sites[i] = raster;
    else if (sliced)
      rq.column_sites[i] = edt::column_key(c[0] + rq.layout.n[0] * c[1], c[2]);
    else
      rq.sites[i] = rq.layout.pack_any(c[0], c[1], c[2]);
  }
  return finish(rq, opt, shape);
}

}  // namespace gpugeom
