// gpugeom_bench_hull3d: 3D convex hull end to end (host points in, host arrays out) and with the
// points and the result on the GPU, over distributions and sizes on each backend, with CGAL's
// convex_hull_3 timed on the same points in the same run when the build found CGAL. Also the
// thesis' scalability test: n fixed, k points on a sphere and the rest strictly inside
// ("scal:K" as a distribution). --save DIR writes every input as .npy for the Qhull anchor
// (bench/anchor_hull3d.py).
#include <array>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench_csv.hpp"
#include "exec/tuning.hpp"
#include "device_timing.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/hull3d.hpp"
#include "gpugeom/io.hpp"
#include "gpugeom/spatial.hpp"
#include "verify.hpp"

#ifdef GG_BENCH_CGAL
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>
#endif

using namespace gpugeom;

namespace {
using clk = std::chrono::steady_clock;

// k points on the sphere of radius 0.45 around (0.5, 0.5, 0.5), n - k in the ball of radius
// 0.44 (inside the hull of the sphere points once k is more than a handful).
std::vector<Point3> scalability(std::int64_t n, std::int64_t k) {
  auto s = generate3d("sphere", k, 3);
  auto b = generate3d("ball", n - k, 4);
  for (auto& p : b)
    p = {0.5 + (p.x - 0.5) * (0.44 / 0.45), 0.5 + (p.y - 0.5) * (0.44 / 0.45),
         0.5 + (p.z - 0.5) * (0.44 / 0.45)};
  s.insert(s.end(), b.begin(), b.end());
  std::shuffle(s.begin(), s.end(), std::mt19937_64(5));
  return s;
}

double cgal_ms(const std::vector<Point3>& p, std::int64_t& vertices) {
#ifdef GG_BENCH_CGAL
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<K::Point_3> in;
  in.reserve(p.size());
  for (auto& q : p) in.emplace_back(q.x, q.y, q.z);
  CGAL::Surface_mesh<K::Point_3> sm;
  const auto t0 = clk::now();
  CGAL::convex_hull_3(in.begin(), in.end(), sm);
  const double ms = bench::ms_since(t0);
  vertices = std::int64_t(sm.number_of_vertices());
  return ms;
#else
  (void)p;
  vertices = -1;
  return -1;
#endif
}
}  // namespace

std::vector<std::array<std::int32_t, 3>> facets(const ConvexHull3d& h) {
  return verify::canonical_triangles(h.triangles.data(), h.num_facets);
}

int main(int argc, char** argv) {
  std::string dists = "ball", sizes = "1e5,1e6", backends = "all", csv, save,
              methods = "incremental";
  int reps = 3;
  std::int64_t cgal_max = 0;
  bool check = false, presort = false, rounds = false;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--dists")
      dists = next();
    else if (a == "--sizes")
      sizes = next();
    else if (a == "--backend")
      backends = next();
    else if (a == "--reps")
      reps = std::max(1, std::stoi(next()));
    else if (a == "--cgal")
      cgal_max = std::int64_t(std::stod(next()));
    else if (a == "--check")
      check = true;
    else if (a == "--csv")
      csv = next();
    else if (a == "--save")
      save = next();
    else if (a == "--methods")  // incremental,digital: a row each (digital: same facets?)
      methods = next();
    else if (a == "--presort" && next() == "hilbert")
      presort = true;
    else if (a == "--rounds")  // the CPU rows also with the GPU's schedule (the rounds): "cpu-r"
      rounds = true;
    else {
      std::cout << "usage: gpugeom_bench_hull3d [--dists ball,uniform,thin_box,thin_sphere,sphere,"
                   "scal:10000] [--sizes 1e6,1e7] [--backend cpu|cuda|all] [--reps 3] [--cgal "
                   "MAX_N] [--check] [--csv FILE] [--save DIR] [--presort hilbert] [--methods "
                   "incremental,digital] [--rounds]\n";
      return a == "--help" ? 0 : 2;
    }
  }
  if (!save.empty() && !bench::make_save_dir(save)) return 2;
  struct Config {
    Backend b;
    Method m;
    bool rounds = false;  // the CPU executor on the GPU's schedule
    std::string bk() const { return std::string(backend_name(b)) + (rounds ? "-r" : ""); }
  };
  std::vector<Config> cfgs;
  for (Backend b : bench::backends(backends)) {
    std::stringstream ms(methods);
    for (std::string m; std::getline(ms, m, ',');)
      if (!m.empty()) {
        cfgs.push_back({b, parse_method(m)});
        if (rounds && b == Backend::Cpu) cfgs.push_back({b, parse_method(m), true});
      }
  }
  auto tuned_rounds = std::make_shared<detail::Tuning>();
  tuned_rounds->hull3d.rounds = true;
  const std::string gpu = query_device().available ? query_device().name : "none";
  std::printf("GPU: %s\n", gpu.c_str());
  std::ofstream f = bench::open_bench_csv(csv);
  std::printf("%-18s %10s %-5s %9s %9s %8s %9s %7s %9s %8s %9s %s\n", "distribution", "n", "bk",
              "total ms", "on-device", "copies", "construct", "flip", "vertices", "rounds",
              "CGAL ms", "check");
  std::stringstream ds(dists);
  for (std::string d; std::getline(ds, d, ',');) {
    if (d.empty()) continue;
    for (double nn : bench::numbers(sizes)) {
      const std::int64_t n = std::int64_t(nn);
      std::vector<Point3> pts;
      std::string name = d;
      if (d.rfind("scal:", 0) == 0) {
        const std::int64_t k = std::int64_t(std::stod(d.substr(5)));
        if (k >= n) continue;
        pts = scalability(n, k);
      } else {
        pts = generate3d(d, n, 1);
      }
      if (presort) {  // the input in Hilbert order, outside the timed calls: does order matter?
        const auto o = hilbert_order(pts, Backend::Cpu);
        std::vector<Point3> q(pts.size());
        for (std::size_t i = 0; i < o.size(); ++i) q[i] = pts[std::size_t(o[i])];
        pts.swap(q);
        name += "+hilbert";
      }
      if (!save.empty()) {
        io::PointSet ps;
        ps.dim = 3;
        ps.coords.assign(&pts.data()->x, &pts.data()->x + 3 * pts.size());
        io::write_points(save + "/" + (d.rfind("scal:", 0) == 0 ? "scal_" + d.substr(5) : d) + "_" +
                             std::to_string(n) + ".npy",
                         ps);
      }
      // Ours first, CGAL after: CGAL's long single-threaded run, when it came first, left the
      // next row's host copies up to 6x slower on the lent machine (cause not established).
      struct Timed {
        ConvexHull3d r;
        std::vector<double> t;
        double dev = -1;
      };
      std::vector<Timed> timed;
      for (const Config& cfg : cfgs) {
        const Backend b = cfg.b;
        Hull3dOptions o;
        o.backend = b;
        o.method = cfg.m;
        if (cfg.rounds) o.tuning = tuned_rounds;
        Timed x;
        x.r = convex_hull3d(pts, o);  // warm-up
        for (int k = 0; k < reps; ++k) {
          x.r = {};  // (the last run's result freed before the clock: not this call's work)
          const auto t0 = clk::now();
          x.r = convex_hull3d(pts, o);
          x.t.push_back(bench::ms_since(t0));
        }
        std::sort(x.t.begin(), x.t.end());
        if (b == Backend::Cuda)
          x.dev = bench::device_resident_ms(pts, reps, [o](const double* d, std::int64_t n) {
            Hull3dOptions od = o;
            od.into = {};
            convex_hull3d_device(d, n, od);
          });
        timed.push_back(std::move(x));
      }
      std::int64_t cgal_v = -1;
      const double cg = n <= cgal_max ? cgal_ms(pts, cgal_v) : -1;
      for (std::size_t bi = 0; bi < cfgs.size(); ++bi) {
        const Backend b = cfgs[bi].b;
        ConvexHull3d& r = timed[bi].r;
        const std::vector<double>& t = timed[bi].t;
        const double med = t[t.size() / 2];
        std::string verdict = cgal_v >= 0 ? (std::int64_t(r.vertices.size()) == cgal_v
                                                 ? "vertices as CGAL"
                                                 : "VERTEX COUNT DIFFERS FROM CGAL")
                                          : "";
        if (cfgs[bi].m == Method::Digital)
          for (std::size_t bj = 0; bj < cfgs.size(); ++bj)
            if (cfgs[bj].b == b && cfgs[bj].rounds == cfgs[bi].rounds &&
                cfgs[bj].m == Method::Incremental)
              verdict += facets(r) == facets(timed[bj].r) ? " same facets as incremental"
                                                          : " FACETS DIFFER FROM INCREMENTAL";
        if (check) {
          const auto rep = verify::check_hull3d(&pts.data()->x, n, r.triangles.data(),
                                                std::int64_t(r.num_facets), 2'000'000'000LL);
          verdict += rep.ok ? " valid" : " INVALID: " + rep.message;
        }
        const double dev = timed[bi].dev;
        std::printf("%-18s %10lld %-5s %9.1f %9.1f %8.1f %9.1f %7.1f %9zu %8lld %9.1f %s\n",
                    (cfgs[bi].m == Method::Digital ? name + " digital" : name).c_str(),
                    (long long)n, cfgs[bi].bk().c_str(), med, dev,
                    bench::phase_ms(r.stats, "upload") + bench::phase_ms(r.stats, "copy_back"),
                    bench::phase_ms(r.stats, "construct"), bench::phase_ms(r.stats, "flip"),
                    r.vertices.size(), (long long)(r.stats.insert_rounds + r.stats.flip_rounds), cg,
                    verdict.c_str());
        std::printf("   ");
        for (auto& ph : r.stats.phase_ms) std::printf(" %s %.1f", ph.first.c_str(), ph.second);
        std::printf(" ms;");
        for (auto& c : r.stats.counter_map())
          std::printf(" %s %lld", c.first.c_str(), (long long)c.second);
        std::printf("; end-to-end runs:");
        for (double x : t) std::printf(" %.1f", x);
        if (b == Backend::Cuda)  // points in; facets, neighbours, vertices and planes out
          std::printf("; bus floor %.2f ms",
                      bench::bus_floor_ms(24.0 * n + 56.0 * r.num_facets + 4.0 * r.num_vertices));
        std::printf("\n");
        std::fflush(stdout);
        if (f)
          f << "hull3d," << (cfgs[bi].m == Method::Digital ? name + "+digital" : name) << "," << n
            << "," << cfgs[bi].bk() << "," << (b == Backend::Cuda ? gpu : "cpu") << ",0," << med
            << ",0," << (dev > 0 ? dev : 0) << "," << med << ","
            << double(r.stats.exact_predicates) / std::max<double>(1, n) << "\n";
      }
      if (f && cg >= 0)
        f << "hull3d," << name << "," << n << ",cgal,cpu-1core,0," << cg << ",0,0," << cg << ",0\n";
    }
  }
  return 0;
}
