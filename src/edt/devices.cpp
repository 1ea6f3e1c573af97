// distance_transform_devices: the grid split along axis 0 into one slab per device, each slab
// computed by the slab transform (EdtOptions::slab) on its own host thread and device, straight
// into its place in the whole grid's outputs. Two rounds of threads: every slab's column bounds
// first (a slab needs its neighbours'), then the transforms.
#include <omp.h>

#include <algorithm>
#include <exception>
#include <string>
#include <thread>

#include "base/clock.hpp"
#include "base/on_threads.hpp"
#include "edt/entries.hpp"
#include "gpugeom/scalar_type.hpp"
#include "gpugeom/multi_gpu.hpp"

namespace gpugeom {

namespace {

using detail::on_threads;

// An output of the whole grid: the caller's array (checked by edt::checked_outputs) or the
// result's.
template <class T>
OutBuffer<T> whole_output(OutBuffer<T> given, HostVector<T>& own, std::int64_t count) {
  if (given) return given;
  own.resize(std::size_t(count));
  return {own.data(), count};
}

template <class T>
OutBuffer<T> part(const OutBuffer<T>& whole, std::int64_t first, std::int64_t count) {
  if (!whole) return {};
  return {whole.data + first, count};
}

}  // namespace

EdtResult distance_transform_devices(const GridView& g, SiteRule rule,
                                     const std::vector<int>& devices_in, const EdtOptions& opt) {
  if (!g.data) throw Error(ErrorCode::InvalidArgument, "the grid's data pointer is null");
  const std::size_t nd = g.shape.size();
  if (nd < 3 || nd > 8)
    throw Error(ErrorCode::InvalidArgument,
                "distance_transform_devices takes grids of 3 to 8 axes (give a 2D grid as (rows, "
                "1, columns)), got " +
                    std::to_string(nd));
  if (opt.labels)
    throw Error(ErrorCode::InvalidArgument,
                "distance_transform_devices gives no labels (a slab cannot rank the whole grid's "
                "sites): ask for features, or use distance_transform");
  if (!opt.slices.empty() || opt.slab.extent)
    throw Error(ErrorCode::InvalidArgument,
                "distance_transform_devices splits the grid itself: no slices or slab in opt");
  if (opt.threads < 0)
    throw Error(ErrorCode::InvalidArgument, "threads must be 0 (all) or positive");
  const bool iso = edt::checked_outputs(g.shape, opt);  // before any work
  std::vector<int> devices = devices_in;
  const Backend b = resolve_backend(opt.backend, devices.empty() ? -1 : devices[0]);
  if (devices.empty()) {
    const int count = b == Backend::Cuda ? query_device().device_count : 1;
    for (int d = 0; d < std::max(1, count); ++d) devices.push_back(d);
  }
  std::int64_t n = 1;
  for (auto e : g.shape) {
    if (e < 1) throw Error(ErrorCode::InvalidInput, "the grid is empty");
    n *= e;
  }
  const std::int64_t n0 = g.shape[0], plane = n / n0;
  const std::size_t k = std::size_t(std::min<std::int64_t>(std::int64_t(devices.size()), n0));
  std::vector<std::int64_t> start(k + 1);
  for (std::size_t i = 0; i <= k; ++i) start[i] = n0 * std::int64_t(i) / std::int64_t(k);
  const int all = opt.threads > 0 ? opt.threads : omp_get_max_threads();
  RunOptions run;
  run.threads = std::max(1, all / int(k));
  const std::size_t elem = io::scalar_size(g.type);
  auto slab_view = [&](std::size_t i) {
    GridView v = g;
    v.data = static_cast<const unsigned char*>(g.data) + std::size_t(start[i] * plane) * elem;
    v.shape[0] = start[i + 1] - start[i];
    return v;
  };

  // Every slab's first and last sites per column, then each slab's bounds: the nearest site
  // before it (a running maximum) and after it (a running minimum).
  const double t0 = now_ms();
  std::vector<ColumnSiteBounds> cb(k);
  on_threads(k,
             [&](std::size_t i) { cb[i] = column_site_bounds(slab_view(i), rule, start[i], run); });
  std::int64_t with = 0;
  for (auto& c : cb) with += c.columns_with_sites;
  if (with == 0)
    throw Error(ErrorCode::InvalidInput, std::string("the grid has no site (no ") +
                                             (rule == SiteRule::NonZero ? "nonzero" : "zero") +
                                             " element): every distance would be infinite");
  std::vector<EdtSlab> slabs(k);
  for (std::size_t i = 0; i < k; ++i) {
    slabs[i].extent = n0;
    slabs[i].first = start[i];
    slabs[i].before.assign(std::size_t(plane), -1);
    slabs[i].after.assign(std::size_t(plane), -1);
  }
  for (std::size_t i = 1; i < k; ++i)
    for (std::int64_t c = 0; c < plane; ++c) {
      const std::int64_t last = cb[i - 1].last[std::size_t(c)];
      slabs[i].before[std::size_t(c)] = last >= 0 ? last : slabs[i - 1].before[std::size_t(c)];
    }
  for (std::size_t i = k - 1; i-- > 0;)
    for (std::int64_t c = 0; c < plane; ++c) {
      const std::int64_t first = cb[i + 1].first[std::size_t(c)];
      slabs[i].after[std::size_t(c)] = first >= 0 ? first : slabs[i + 1].after[std::size_t(c)];
    }
  cb.clear();
  const double bounds_ms = now_ms() - t0;

  // The whole grid's outputs, each slab writing its part in place; features are laid out axis
  // by axis, so a slab's come back and are copied into each axis' part.
  EdtResult r;
  r.shape = g.shape;
  OutBuffer<std::int64_t> sq_int;
  OutBuffer<double> sq_real, d64;
  OutBuffer<float> d32;
  OutBuffer<std::int32_t> feat;
  if (opt.squared && iso) sq_int = whole_output(opt.into.sqdist_int, r.sqdist_int, n);
  if (opt.squared && !iso) sq_real = whole_output(opt.into.sqdist_real, r.sqdist_real, n);
  if (opt.distance == 32) d32 = whole_output(opt.into.distance32, r.distance32, n);
  if (opt.distance == 64) d64 = whole_output(opt.into.distance64, r.distance64, n);
  if (opt.features) feat = whole_output(opt.into.features, r.features, std::int64_t(nd) * n);
  const double t1 = now_ms();
  std::vector<EdtStats> stats(k);
  on_threads(k, [&](std::size_t i) {
    EdtOptions o = opt;
    o.backend = b;
    o.device = b == Backend::Cuda ? devices[i] : -1;
    o.stream = nullptr;
    o.threads = run.threads;
    o.slab = std::move(slabs[i]);
    const std::int64_t first = start[i] * plane, count = (start[i + 1] - start[i]) * plane;
    o.into = {};
    o.into.sqdist_int = part(sq_int, first, count);
    o.into.sqdist_real = part(sq_real, first, count);
    o.into.distance32 = part(d32, first, count);
    o.into.distance64 = part(d64, first, count);
    EdtResult s = distance_transform(slab_view(i), rule, o);
    for (std::size_t a = 0; a < (opt.features ? nd : 0); ++a)
      std::copy(s.features.begin() + std::ptrdiff_t(a * std::size_t(count)),
                s.features.begin() + std::ptrdiff_t((a + 1) * std::size_t(count)),
                feat.data + std::int64_t(a) * n + first);
    stats[i] = std::move(s.stats);
  });
  r.stats.backend = b;
  r.stats.phase_ms.push_back({"bounds", bounds_ms});
  r.stats.phase_ms.push_back({"slabs", now_ms() - t1});
  for (std::size_t i = 0; i < k; ++i)
    for (auto& [name, ms] : stats[i].phase_ms)
      r.stats.phase_ms.push_back({"slab" + std::to_string(i) + "_" + name, ms});
  r.stats.slabs = std::int64_t(k);
  return r;
}

}  // namespace gpugeom
