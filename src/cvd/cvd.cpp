// Public entry of the centroidal Voronoi diagram: checks the density and the options,
// quantises the density onto the Voronoi grid, draws or places the initial sites, runs the
// backend and converts back to density pixels.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <unordered_set>

#include "base/stats_fields.hpp"
#include "cvd/cvd_backend.hpp"
#include "edt/edt_backend.hpp"
#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "gpugeom/cvd.hpp"

namespace gpugeom {

namespace {

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

// The request for a density the caller holds (checked here: shape, sizes, initial sites; its
// values are checked on the executor).
cvd::Request make_request(const GridView& g, const CvdOptions& opt, bool on_device) {
  check_options(opt);
  if (!g.data) bad_arg("the density's data pointer is null");
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
  cvd::Request rq;
  rq.layout = edt::make_layout(gshape, false, edt::Packing::Bits);
  const edt::Layout& L = rq.layout;
  // Every sum is exact in 64 bits when 65535 * points * extent < 2^63.
  const double bound = cvd::kLevels * double(gcount) * double(std::max({L.n[0], L.n[1], L.n[2]}));
  if (bound >= 9.2e18) bad_input("the Voronoi grid is too large for exact 64-bit moments");
  rq.density = g.data;
  rq.type = g.type;
  rq.on_device = on_device;
  rq.pext[0] = g.shape[nd - 1];
  rq.pext[1] = g.shape[nd - 2];
  rq.pext[2] = nd == 3 ? g.shape[0] : 1;
  rq.s = s;
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
  }
  rq.into = opt.into;
  rq.num_sites = opt.num_sites;
  // The site count is known before any work (drawn: exactly num_sites, or an error).
  const std::int64_t ns =
      opt.initial_sites.empty() ? opt.num_sites : std::int64_t(opt.initial_sites.size()) / nd;
  deliver::check(opt.into.sites, ns * nd, "sites");
  deliver::check(opt.into.mass, ns, "mass");
  rq.seed = opt.seed;
  rq.max_iterations = opt.max_iterations;
  rq.run = static_cast<const RunOptions&>(opt);
  rq.move_tol2 = (opt.move_tolerance * s) * (opt.move_tolerance * s);
  rq.energy_tol = opt.energy_tolerance;
  return rq;
}

// Runs the backend; energies and progress in density units (known once the backend has the
// density's maximum: the progress callback gets them through `unit`).
void run(Backend b, cvd::Request& rq, const CvdOptions& opt, cvd::Output& out, CvdStats& st) {
  const int s = rq.s;
  if (opt.progress)
    rq.progress = [&opt, &out, s](int it, const cvd::Scalars& sc) {
      CvdProgress p;
      p.iteration = it;
      p.energy = sc.energy * out.unit_energy;
      p.max_move = std::sqrt(double(sc.max_move2)) / s;
      p.moved = std::int64_t(sc.moved);
      return opt.progress(p);
    };
  st.backend = b;
  st.grid_points = rq.layout.count();
  GG_ENTRIES(b, cvd).lloyd(rq, out, st);
}

// What both results share: the energies in density units, the iteration count and the verdict.
template <class Result>
void finish(const cvd::Output& out, Result& r) {
  r.energy.resize(out.energy.size());
  for (std::size_t i = 0; i < out.energy.size(); ++i) r.energy[i] = out.energy[i] * out.unit_energy;
  r.iterations = out.iterations;
  r.converged = out.converged;
}

}  // namespace

// clang-format off
#define GG_CVD_COUNTERS(X) X(grid_points) X(sites) X(iterations)
// clang-format on
GG_COUNTER_MAP(CvdStats, GG_CVD_COUNTERS);
#undef GG_CVD_COUNTERS

CvdResult centroidal_voronoi(const GridView& g, const CvdOptions& opt) {
  cvd::Request rq = make_request(g, opt, false);
  CvdResult r;
  r.dim = rq.layout.nd;
  cvd::Output out;
  run(resolve_backend(opt.backend, opt.device), rq, opt, out, r.stats);
  r.sites = std::move(out.sites);
  r.mass = std::move(out.mass);
  r.num_sites = out.num_sites;
  finish(out, r);
  return r;
}

DeviceCvdResult centroidal_voronoi_device(const GridView& g, const CvdOptions& opt) {
  cvd::Request rq = make_request(g, opt, true);
  rq.device_out = true;
  DeviceCvdResult r;
  r.dim = rq.layout.nd;
  r.backend = device_entry_backend(opt.backend, opt.device, "centroidal_voronoi_device");
  cvd::Output out;
  run(r.backend, rq, opt, out, r.stats);
  r.num_sites = out.num_sites;
  r.sites = std::move(out.dev_sites);
  r.mass = std::move(out.dev_mass);
  finish(out, r);
  return r;
}

}  // namespace gpugeom
