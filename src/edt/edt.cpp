// Public entry of the distance transform: checks the request, packs the sites, picks the
// backend, and returns outputs in C axis order.
#include <cmath>
#include <string>

#include "edt/edt_backend.hpp"
#include "base/hd.hpp"
#include "gpugeom/edt.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom {

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

// sliced: only slices of nx * ny voxels are held at once, so only they must fit int32 indexing.
Layout make_layout(const std::vector<std::int64_t>& shape, bool sliced) {
  if (shape.size() != 2 && shape.size() != 3)
    throw Error(ErrorCode::InvalidInput, "the distance transform needs a 2D or 3D grid, got " +
                                             std::to_string(shape.size()) + " dimensions");
  Layout L;
  L.nd = int(shape.size());
  for (int a = 0; a < L.nd; ++a) {
    const std::int64_t e = shape[L.nd - 1 - a];  // internal axis a = C axis nd-1-a
    if (e <= 0) throw Error(ErrorCode::InvalidInput, "grid extents must be positive");
    L.n[a] = e;
  }
  int shift = 0;
  for (int a = 0; a < 3; ++a) {
    const int b = bits_for(L.n[a]);
    L.shift[a] = shift;
    L.mask[a] = b ? std::uint32_t((std::uint64_t(1) << b) - 1) : 0;
    shift += b;
  }
  if (shift > 32)
    throw Error(ErrorCode::InvalidInput,
                "grid extents too large: the coordinates of a voxel must fit 32 bits together "
                "(e.g. 1024 x 1024 x 4096, 65536 x 65536), these need " +
                    std::to_string(shift));
  const std::int64_t held = sliced ? L.n[0] * L.n[1] : L.count();
  if (held >= (std::int64_t(1) << 31) - 1)
    throw Error(ErrorCode::InvalidInput,
                "grid too large for one pass (" + std::to_string(L.count()) +
                    " voxels, at most 2^31-2): use the slice-by-slice mode (slices) for volumes");
  return L;
}

}  // namespace edt

namespace {

edt::Metric make_metric(const std::vector<double>& sampling, int nd) {
  edt::Metric m;
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

EdtResult finish(edt::Request& rq, const EdtOptions& opt, const std::vector<std::int64_t>& shape) {
  if (opt.distance != 0 && opt.distance != 32 && opt.distance != 64)
    throw Error(ErrorCode::InvalidArgument, "distance must be 0, 32 or 64 (bits)");
  rq.method = opt.method;
  for (int a = 0; a < 3; ++a) rq.tune.bands[a] = opt.bands[a];
  rq.tune.window_reach = opt.window_reach;
  rq.tune.tiles = opt.tiles;
  rq.run = static_cast<const RunOptions&>(opt);
  rq.want_sqdist = opt.squared;
  rq.want_distance = opt.distance;
  rq.want_features = opt.features;
  rq.want_labels = opt.labels;
  EdtResult r;
  r.shape = shape;
  if (!opt.slices.empty()) {
    if (shape.size() != 3) throw Error(ErrorCode::InvalidArgument, "slices apply to 3D grids only");
    if (opt.method != EdtMethod::Pba)
      throw Error(ErrorCode::InvalidArgument, "slices need the PBA method");
    for (auto z : opt.slices)
      if (z < 0 || z >= shape[0])
        throw Error(ErrorCode::InvalidArgument, "slice " + std::to_string(z) + " is outside 0.." +
                                                    std::to_string(shape[0] - 1));
    rq.slices = opt.slices;
    r.shape[0] = std::int64_t(opt.slices.size());
  }
  const Backend b = resolve_backend(opt.backend, opt.device);
  r.stats.backend = b;
  edt::Output out;
#ifdef GPUGEOM_HAVE_CUDA
  if (b == Backend::Cuda)
    edt::cuda_impl::run(rq, out, r.stats);
  else
    edt::cpu_impl::run(rq, out, r.stats);
#else
  edt::cpu_impl::run(rq, out, r.stats);
#endif
  r.sqdist_int = std::move(out.sqdist_int);
  r.sqdist_real = std::move(out.sqdist_real);
  r.distance32 = std::move(out.dist32);
  r.distance64 = std::move(out.dist64);
  r.features = std::move(out.features);
  r.labels = std::move(out.labels);
  return r;
}

}  // namespace

EdtResult distance_transform(const io::Grid& g, SiteRule rule, const EdtOptions& opt) {
  edt::Request rq;
  rq.layout = edt::make_layout(g.shape, !opt.slices.empty());
  rq.metric = make_metric(opt.sampling, rq.layout.nd);
  const std::int64_t n = g.count();
  std::vector<std::uint8_t> mask(n);
  std::int64_t sites = 0;
  bool finite = true;
  const bool bytes = g.type == io::ScalarType::U8 || g.type == io::ScalarType::Bool;
#pragma omp parallel for reduction(+ : sites) reduction(&& : finite)
  for (std::int64_t i = 0; i < n; ++i) {
    const double v = bytes ? double(g.data[i]) : g.value(i);  // bytes: the common, fast case
    finite = finite && !std::isnan(v);
    const bool s = rule == SiteRule::NonZero ? v != 0 : v == 0;
    mask[i] = s;
    sites += s;
  }
  if (!finite) throw Error(ErrorCode::InvalidInput, "the grid contains NaN values");
  if (sites == 0)
    throw Error(ErrorCode::InvalidInput, std::string("the grid has no site (no ") +
                                             (rule == SiteRule::NonZero ? "nonzero" : "zero") +
                                             " element): every distance would be infinite");
  rq.site_count = sites;
  if (opt.slices.empty()) {
    rq.mask = mask.data();
  } else {  // slice by slice: the device holds the site list and one slice, never the volume
    rq.sites.reserve(std::size_t(sites));
    const edt::Layout& L = rq.layout;
    for (std::int64_t i = 0; i < n; ++i)  // raster order: labels are raster ranks as usual
      if (mask[i])
        rq.sites.push_back(L.pack(i % L.n[0], (i / L.n[0]) % L.n[1], i / (L.n[0] * L.n[1])));
  }
  return finish(rq, opt, g.shape);
}

EdtResult distance_transform_sites(const std::vector<std::int64_t>& shape,
                                   const std::vector<std::int64_t>& sites, const EdtOptions& opt) {
  edt::Request rq;
  rq.layout = edt::make_layout(shape, !opt.slices.empty());
  rq.metric = make_metric(opt.sampling, rq.layout.nd);
  const int nd = rq.layout.nd;
  if (sites.empty() || sites.size() % nd)
    throw Error(ErrorCode::InvalidInput,
                sites.empty() ? "no sites given: every distance would be infinite"
                              : "the site list is not a whole number of coordinates");
  const std::int64_t ns = std::int64_t(sites.size()) / nd;
  if (ns >= (std::int64_t(1) << 31))
    throw Error(ErrorCode::InvalidInput, "too many sites (at most 2^31-1)");
  rq.sites.resize(ns);
  rq.site_count = ns;
  for (std::int64_t i = 0; i < ns; ++i) {
    std::int64_t c[3] = {0, 0, 0};
    for (int j = 0; j < nd; ++j) {
      const std::int64_t v = sites[i * nd + j];
      if (v < 0 || v >= shape[j])
        throw Error(ErrorCode::InvalidInput,
                    "site " + std::to_string(i) + " lies outside the grid (coordinate " +
                        std::to_string(v) + " on axis " + std::to_string(j) + ")");
      c[nd - 1 - j] = v;
    }
    rq.sites[i] = rq.layout.pack(c[0], c[1], c[2]);
  }
  return finish(rq, opt, shape);
}

}  // namespace gpugeom
