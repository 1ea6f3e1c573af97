// Public entry of the centroidal Voronoi diagram: checks the density and the options,
// quantises the density onto the Voronoi grid, draws or places the initial sites, runs the
// backend and converts back to density pixels.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <unordered_set>

#include "cvd/cvd_backend.hpp"
#include "edt/edt_backend.hpp"
#include "gpugeom/cvd.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom {

namespace {

constexpr double kLevels = 65535;  // weights are quantised to 16 bits of the maximum

[[noreturn]] void bad_arg(const std::string& m) {
  throw Error(ErrorCode::InvalidArgument, m);
}
[[noreturn]] void bad_input(const std::string& m) {
  throw Error(ErrorCode::InvalidInput, m);
}

void check_options(const CvdOptions& o) {
  if (o.supersample < 1 || o.supersample > 64) bad_arg("supersample must be in 1..64");
  if (o.max_iterations < 1) bad_arg("max_iterations must be at least 1");
  if (!(o.move_tolerance >= 0) || !std::isfinite(o.move_tolerance))
    bad_arg("move_tolerance must be finite and >= 0");
  if (!(o.energy_tolerance >= 0) || !(o.energy_tolerance < 1))
    bad_arg("energy_tolerance must be in [0, 1)");
  if (o.initial_sites.empty() && o.num_sites < 1) bad_arg("num_sites must be at least 1");
}

// Density-weighted draw of distinct grid points: a pixel with probability proportional to its
// weight (cumulative sums over pixels, not grid points: s^d times less memory when
// supersampled), then one of its s^d grid points uniformly. Returns grid coordinates, nd per
// site, internal axis order.
std::vector<std::int32_t> draw_sites(const edt::Layout& L, const std::vector<std::uint32_t>& q,
                                     const std::int64_t pext[3], int s, std::int64_t want,
                                     std::uint64_t seed) {
  const std::int64_t np = std::int64_t(q.size());
  std::int64_t per = 1;  // grid points per pixel
  for (int a = 0; a < L.nd; ++a) per *= s;
  std::vector<std::uint64_t> cum(std::size_t(np) + 1, 0);
  std::int64_t positive = 0;
  for (std::int64_t i = 0; i < np; ++i) {
    cum[i + 1] = cum[i] + q[i];
    positive += q[i] > 0 ? per : 0;
  }
  if (want > positive)
    bad_input("asked for " + std::to_string(want) + " sites but the density is positive at only " +
              std::to_string(positive) +
              " grid points: ask for fewer sites or a larger supersample");
  if (want >= (std::int64_t(1) << 31)) bad_input("too many sites (at most 2^31-1)");
  // Grid point k (0 <= k < per) of pixel p, as a raster index of the grid.
  auto point = [&](std::int64_t p, std::int64_t k) {
    const std::int64_t px = p % pext[0], py = (p / pext[0]) % pext[1], pz = p / (pext[0] * pext[1]);
    const std::int64_t x = px * s + k % s, y = py * s + (k / s) % s, z = pz * s + k / (s * s);
    return x + L.n[0] * (y + L.n[1] * (L.nd == 3 ? z : 0));
  };
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::uint64_t> pick(0, cum[np] - 1);
  std::uniform_int_distribution<std::int64_t> sub(0, per - 1);
  std::unordered_set<std::int64_t> used;
  used.reserve(std::size_t(want) * 2);
  std::vector<std::int64_t> chosen;
  chosen.reserve(std::size_t(want));
  const std::int64_t tries = 50 * want + 1000;
  for (std::int64_t k = 0; k < tries && std::int64_t(chosen.size()) < want; ++k) {
    const std::uint64_t r = pick(rng);  // the pixel whose weight interval holds r
    const std::int64_t p =
        std::int64_t(std::upper_bound(cum.begin(), cum.end(), r) - cum.begin()) - 1;
    const std::int64_t i = point(p, sub(rng));
    if (used.insert(i).second) chosen.push_back(i);
  }
  for (std::int64_t p = 0; p < np && std::int64_t(chosen.size()) < want; ++p)  // nearly full
    for (std::int64_t k = 0; k < per && q[p] > 0 && std::int64_t(chosen.size()) < want; ++k)
      if (used.insert(point(p, k)).second) chosen.push_back(point(p, k));
  std::vector<std::int32_t> out;
  out.reserve(chosen.size() * L.nd);
  for (std::int64_t i : chosen) {
    out.push_back(std::int32_t(i % L.n[0]));
    out.push_back(std::int32_t((i / L.n[0]) % L.n[1]));
    if (L.nd == 3) out.push_back(std::int32_t(i / (L.n[0] * L.n[1])));
  }
  return out;
}

}  // namespace

CvdResult centroidal_voronoi(const io::Grid& g, const CvdOptions& opt) {
  check_options(opt);
  const int nd = int(g.shape.size());
  if (nd != 2 && nd != 3)
    bad_input("a centroidal Voronoi diagram needs a 2D or 3D density, got " + std::to_string(nd) +
              " dimensions");
  const int s = opt.supersample;
  std::vector<std::int64_t> gshape = g.shape;
  std::int64_t gcount = 1;
  for (auto& e : gshape) {
    if (e <= 0) bad_input("density extents must be positive");
    e *= s;
    gcount *= e;
  }
  if (gcount >= (std::int64_t(1) << 31) - 1)
    bad_input("the Voronoi grid would have " + std::to_string(gcount) +
              " points (at most 2^31-2): use a smaller supersample or density");
  const edt::Layout L = edt::make_layout(gshape);
  // Every sum is exact in 64 bits when 65535 * points * extent < 2^63.
  const double bound = kLevels * double(gcount) * double(std::max({L.n[0], L.n[1], L.n[2]}));
  if (bound >= 9.2e18) bad_input("the Voronoi grid is too large for exact 64-bit moments");

  // Density: finite, non-negative, not all zero; quantised to 16 bits of its maximum.
  const std::int64_t n = g.count();
  double vmax = 0;
  bool ok = true;
  for (std::int64_t i = 0; i < n; ++i) {
    const double v = g.value(i);
    ok = ok && std::isfinite(v) && v >= 0;
    vmax = std::max(vmax, v);
  }
  if (!ok) bad_input("the density must be finite and non-negative everywhere");
  if (!(vmax > 0)) bad_input("the density is zero everywhere: no cell has a centroid");
  std::vector<std::uint32_t> q(static_cast<std::size_t>(n));
  for (std::int64_t i = 0; i < n; ++i)
    q[i] = std::uint32_t(std::lround(g.value(i) / vmax * kLevels));

  cvd::Request rq;
  rq.layout = L;
  rq.weights.resize(std::size_t(gcount));
  const std::int64_t px = g.shape[nd - 1], py = g.shape[nd - 2];
#pragma omp parallel for
  for (std::int64_t i = 0; i < gcount; ++i) {  // grid point -> its pixel
    const std::int64_t x = i % L.n[0], y = (i / L.n[0]) % L.n[1], z = i / (L.n[0] * L.n[1]);
    rq.weights[i] = q[(x / s) + px * ((y / s) + py * (z / s))];
  }

  if (!opt.initial_sites.empty()) {
    if (opt.initial_sites.size() % nd)
      bad_input("initial_sites is not a whole number of " + std::to_string(nd) + "D points");
    const std::int64_t ns = std::int64_t(opt.initial_sites.size()) / nd;
    rq.sites.resize(opt.initial_sites.size());
    for (std::int64_t i = 0; i < ns; ++i)
      for (int a = 0; a < nd; ++a) {
        const double p = opt.initial_sites[i * nd + a];
        const double gp = std::floor((p + 0.5) * s);  // the grid point whose cell holds p
        if (!std::isfinite(p) || gp < 0 || gp >= double(L.n[a]))
          bad_input("initial site " + std::to_string(i) + " lies outside the density (" + "xyz"[a] +
                    " = " + std::to_string(p) + ")");
        rq.sites[i * nd + a] = std::int32_t(gp);
      }
  } else {
    const std::int64_t pext[3] = {px, py, nd == 3 ? g.shape[0] : 1};
    rq.sites = draw_sites(L, q, pext, s, opt.num_sites, opt.seed);
  }
  const double unit_mass = vmax / kLevels / std::pow(double(s), nd);
  const double unit_energy = unit_mass / (double(s) * s);
  rq.max_iterations = opt.max_iterations;
  rq.run = static_cast<const RunOptions&>(opt);
  rq.move_tol2 = (opt.move_tolerance * s) * (opt.move_tolerance * s);
  rq.energy_tol = opt.energy_tolerance;
  if (opt.progress)
    rq.progress = [&](int it, const cvd::Scalars& sc) {
      CvdProgress p;
      p.iteration = it;
      p.energy = sc.energy * unit_energy;
      p.max_move = std::sqrt(double(sc.max_move2)) / s;
      p.moved = std::int64_t(sc.moved);
      return opt.progress(p);
    };

  CvdResult r;
  r.dim = nd;
  const Backend b = resolve_backend(opt.backend, opt.device);
  r.stats.backend = b;
  r.stats.counters["sites"] = std::int64_t(rq.sites.size()) / nd;
  r.stats.counters["grid_points"] = gcount;
  cvd::Output out;
#ifdef GPUGEOM_HAVE_CUDA
  if (b == Backend::Cuda)
    cvd::cuda_impl::lloyd(rq, out, r.stats);
  else
    cvd::cpu_impl::lloyd(rq, out, r.stats);
#else
  cvd::cpu_impl::lloyd(rq, out, r.stats);
#endif
  r.sites.resize(out.sites.size());
  for (std::size_t i = 0; i < out.sites.size(); ++i) r.sites[i] = (out.sites[i] + 0.5) / s - 0.5;
  r.mass.resize(out.mass.size());
  for (std::size_t i = 0; i < out.mass.size(); ++i) r.mass[i] = double(out.mass[i]) * unit_mass;
  r.energy.resize(out.energy.size());
  for (std::size_t i = 0; i < out.energy.size(); ++i) r.energy[i] = out.energy[i] * unit_energy;
  r.iterations = out.iterations;
  r.converged = out.converged;
  return r;
}

}  // namespace gpugeom
