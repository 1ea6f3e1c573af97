// gpugeom_bench_del2d: 2D Delaunay end to end (host points in, host triangles out) over
// distributions and sizes on each backend, with CGAL's Delaunay_triangulation_2 timed on the
// same points in the same run when the build found CGAL. Points come from the generators, or
// from .npy files (x, y columns) for the terrain contour set (bench/terrain_contours.py).
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <memory>
#include <string>
#include <vector>

#include "bench_csv.hpp"
#include "exec/tuning.hpp"
#include "device_timing.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/io.hpp"
#include "gpugeom/predicates.hpp"
#include "verify.hpp"

#ifdef GG_BENCH_CGAL
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#endif

using namespace gpugeom;

namespace {
using clk = std::chrono::steady_clock;
double cgal_ms(const std::vector<Point2>& p) {
#ifdef GG_BENCH_CGAL
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<K::Point_2> in;
  in.reserve(p.size());
  for (auto& q : p) in.emplace_back(q.x, q.y);
  const auto t0 = clk::now();
  CGAL::Delaunay_triangulation_2<K> dt(in.begin(), in.end());
  const double ms = bench::ms_since(t0);
  if (dt.number_of_faces() == 0) std::printf("(CGAL built no triangle)\n");
  return ms;
#else
  (void)p;
  return -1;
#endif
}
// --sample K: for sizes the full checker cannot take (it keeps every edge in a hash map), K
// triangles drawn by hash are checked exactly, each with its three neighbours: counter-
// clockwise with positive area, every neighbour pointer mutual with the shared edge reversed,
// no vertex of a neighbour strictly inside the triangle's circumcircle (local Delaunay); and,
// over the whole output, the count 2m - 2 - h for m distinct points and h hull edges. With
// every point a vertex (checked always), these are the checker's tests on a sample.
std::string sample_check(const std::vector<Point2>& p, const Triangulation2d& r, std::int64_t k) {
  const std::int64_t nt = r.num_triangles;
  const std::int32_t* t = r.triangles.data();
  const std::int32_t* nb = r.neighbors.data();
  std::int64_t hull = 0, distinct = 0;
#pragma omp parallel for reduction(+ : hull)
  for (std::int64_t i = 0; i < 3 * nt; ++i) hull += nb[i] < 0;
  for (std::int32_t d : r.duplicate_of) distinct += d < 0;
  std::int64_t bad = 0;
#pragma omp parallel for reduction(+ : bad)
  for (std::int64_t j = 0; j < k; ++j) {
    const std::int64_t c = std::int64_t(bench::hash64(std::uint64_t(j), 99) % std::uint64_t(nt));
    const std::int32_t* v = t + 3 * c;
    bool ok = orient2d(p[v[0]], p[v[1]], p[v[2]]) > 0;
    for (int e = 0; e < 3 && ok; ++e) {
      const std::int32_t o = nb[3 * c + e];  // across the edge opposite v[e]
      if (o < 0) continue;
      const std::int32_t a = v[(e + 1) % 3], b = v[(e + 2) % 3];
      int back = -1;
      for (int f = 0; f < 3; ++f)
        if (nb[3 * std::int64_t(o) + f] == c) back = f;
      const std::int32_t* w = t + 3 * std::int64_t(o);
      ok = back >= 0 && w[(back + 1) % 3] == b && w[(back + 2) % 3] == a &&
           incircle(p[v[0]], p[v[1]], p[v[2]], p[w[back]]) <= 0;
    }
    bad += !ok;
  }
  std::string s = std::to_string(k) + " sampled: " + std::to_string(bad) + " wrong";
  if (nt != 2 * distinct - 2 - hull) s += ", WRONG COUNT";
  return s;
}
}  // namespace

// Median time of voronoi2d_device over a triangulation left on the executor by
// delaunay2d_device (points uploaded once; the triangulation not timed). -1 without CUDA.
double voronoi_device_ms(const std::vector<Point2>& p, Backend b, int reps) {
  const std::int64_t n = std::int64_t(p.size());
  Delaunay2dOptions o;
  o.backend = b;
  const auto vo = options_from<Voronoi2dOptions>(o);
  if (b == Backend::Cpu) {
    const auto dt = delaunay2d_device(&p.data()->x, n, o);
    std::vector<double> t;
    for (int k = 0; k < reps; ++k) {
      const auto t0 = clk::now();
      voronoi2d_device(&p.data()->x, n, dt, vo);
      t.push_back(bench::ms_since(t0));
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
  }
  double out = -1;
  bench::device_resident_ms(p, 1, [&](const double* d, std::int64_t m) {
    if (out >= 0) return;  // (the warm-up call does the work)
    const auto dt = delaunay2d_device(d, m, o);
    voronoi2d_device(d, m, dt, vo);  // warm-up
    std::vector<double> t;
    for (int k = 0; k < reps; ++k) {
      const auto t0 = clk::now();
      voronoi2d_device(d, m, dt, vo);
      t.push_back(bench::ms_since(t0));
    }
    std::sort(t.begin(), t.end());
    out = t[t.size() / 2];
  });
  return out;
}

// --digital: the digital method (issue 20) on the same points and executor, for each grid side
// (0: chosen from n), beside the incremental result `inc`: end to end time, its phases, the
// points the sketch left to insertion, flips against the incremental method's, and whether the
// triangles are the incremental method's (as sets).
// csv: where given, a row per grid ("NAME+digital" or "NAME+digitalSIDE"; end to end only).
void digital_rows(const std::string& name, const std::vector<Point2>& pts, Backend b, int reps,
                  const std::string& grids, const Triangulation2d& inc, std::ofstream* csv,
                  const std::string& device) {
  const std::int64_t n = std::int64_t(pts.size());
  std::vector<std::array<std::int32_t, 3>> ref;
  auto tri_set = [](const Triangulation2d& t) {
    return verify::canonical_triangles(t.triangles.data(), t.num_triangles);
  };
  ref = tri_set(inc);
  for (double g : bench::numbers(grids)) {
    Delaunay2dOptions o;
    o.backend = b;
    o.method = Method::Digital;
    o.grid = std::int64_t(g);
    Triangulation2d r;
    std::vector<double> t;
    try {
      r = delaunay2d(pts, o);  // warm-up
      for (int k = 0; k < reps; ++k) {
        r = Triangulation2d{};  // (the last run's result freed before the clock)
        const auto t0 = clk::now();
        r = delaunay2d(pts, o);
        t.push_back(bench::ms_since(t0));
      }
    } catch (const Error& e) {
      std::printf("    digital grid %lld refused: %s\n", (long long)g, e.what());
      continue;
    }
    std::sort(t.begin(), t.end());
    auto& c = r.stats;
    const bool same = tri_set(r) == ref;
    std::printf(
        "  %-20s %10lld %-5s %10.1f  digital %lldx%lld: left to insert %lld (%.1f %%: %lld "
        "sharing a pixel, %lld deleted), flips %lld (incremental %lld), batches %lld, %s%s\n",
        name.c_str(), (long long)n, backend_name(b), t[t.size() / 2], (long long)c.grid_width,
        (long long)c.grid_height, (long long)(n - c.start_vertices),
        100.0 * double(n - c.start_vertices) / double(n), (long long)c.sketch_missing,
        (long long)(c.bad_inner + c.bad_boundary), (long long)c.flips, (long long)inc.stats.flips,
        (long long)c.batches, same ? "identical" : "DIFFERENT TRIANGLES",
        c.digital_fallback ? " (FELL BACK to incremental)" : "");
    std::printf("   ");
    for (auto& ph : r.stats.phase_ms)
      if (ph.first.rfind("insert/", 0) != 0) std::printf(" %s %.1f", ph.first.c_str(), ph.second);
    std::printf("\n");
    std::fflush(stdout);
    if (csv && *csv) {
      const double med = t[t.size() / 2];
      *csv << "delaunay2d," << name << "+digital" << (g > 0 ? std::to_string(std::int64_t(g)) : "")
           << "," << n << "," << backend_name(b) << "," << device << ",0," << med << ",0,0," << med
           << ",0\n";
    }
  }
}

int main(int argc, char** argv) {
  std::string dists = "uniform", sizes = "1e5,1e6", backends = "all", csv, files, digital;
  int reps = 3;
  bool cgal = false, check = false, voronoi = false;
  std::shared_ptr<detail::Tuning> tuning;  // --capacities, --team
  std::int64_t sample = 0;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--dists")
      dists = next();
    else if (a == "--sizes")
      sizes = next();
    else if (a == "--files")
      files = next();
    else if (a == "--backend")
      backends = next();
    else if (a == "--reps")
      reps = std::stoi(next());
    else if (a == "--cgal")
      cgal = true;
    else if (a == "--check")
      check = true;
    else if (a == "--sample")  // K triangles checked exactly (any size)
      sample = std::stoll(next());
    else if (a == "--team") {  // the longest list whose rounds run in a team (-1: none)
      if (!tuning) tuning = std::make_shared<detail::Tuning>();
      tuning->del2d.team_list = std::stoll(next());
    } else if (a == "--capacities") {  // B,L,X: the flip rounds' capacities (0 = the default)
      if (!tuning) tuning = std::make_shared<detail::Tuning>();
      detail::Tuning::Del2d& c = tuning->del2d;
      if (std::sscanf(next().c_str(), "%lld,%lld,%lld", (long long*)&c.batch_points,
                      (long long*)&c.log_records, (long long*)&c.exact_entries) != 3) {
        std::cout << "--capacities takes three counts: batch points, log records, exact entries\n";
        return 2;
      }
    } else if (a == "--digital") {  // grid sides for the digital method (0: automatic)
      digital = next();
    } else if (a == "--voronoi")
      voronoi = true;
    else if (a == "--csv")
      csv = next();
    else {
      std::cout << "usage: gpugeom_bench_del2d [--dists uniform,circle] [--sizes 1e5,1e6] "
                   "[--files a.npy,b.npy] [--backend cpu|cuda|all] [--reps 3] [--cgal] [--check] "
                   "[--sample K] [--capacities B,L,X] [--team N] [--voronoi] [--digital 0,8192] "
                   "[--csv FILE]\n";
      return a == "--help" ? 0 : 2;
    }
  }
  if (reps < 1) {
    std::cout << "--reps takes a count of at least 1 (each row is the median of that many runs)\n";
    return 2;
  }
  struct Input {
    std::string name;
    std::vector<Point2> pts;
  };
  std::vector<Input> inputs;
  std::stringstream ds(dists);
  for (std::string d; std::getline(ds, d, ',');)
    if (!d.empty())
      for (double n : bench::numbers(sizes))
        if (d != "skip") inputs.push_back({d, generate2d(d, std::int64_t(n), 1)});
  std::stringstream fs(files);
  for (std::string f; std::getline(fs, f, ',');) {
    if (f.empty()) continue;
    const io::PointSet ps = io::read_points(f);
    Input in{f.substr(f.find_last_of('/') + 1), {}};
    for (std::size_t i = 0; i < ps.size(); ++i)
      in.pts.push_back({ps.coords[ps.dim * i], ps.coords[ps.dim * i + 1]});
    inputs.push_back(std::move(in));
  }
  const std::vector<Backend> bks = bench::backends(backends);
  const std::string gpu = query_device().available ? query_device().name : "none";
  std::printf("GPU: %s\n", gpu.c_str());
  std::ofstream f = bench::open_bench_csv(csv);
  std::printf("%-22s %10s %-5s %10s %9s %9s %9s %9s %9s %7s %7s %9s %s\n", "distribution", "n",
              "bk", "total ms", "on-device", "prepare", "insert", "output", "Mpts/s", "batches",
              "rounds", "CGAL ms", "vertices / check");
  for (const auto& in : inputs) {
    const std::int64_t n = std::int64_t(in.pts.size());
    const double cg = cgal ? cgal_ms(in.pts) : -1;
    for (Backend b : bks) {
      Delaunay2dOptions o;
      o.backend = b;
      o.tuning = tuning;
      // GPUGEOM_PROFILE=1: per-step times (the library synchronises after each step).
      o.profile = std::getenv("GPUGEOM_PROFILE") != nullptr;
      const double free0 = b == Backend::Cuda ? double(query_device().free_memory) / 1e9 : 0;
      Triangulation2d r;
      try {
        r = delaunay2d(in.pts, o);  // warm-up
      } catch (const Error& e) {    // (a size past memory: reported, and the next one tried)
        std::printf("%-22s %10lld %-5s refused: %s\n", in.name.c_str(), (long long)n,
                    backend_name(b), e.what());
        continue;
      }
      if (b == Backend::Cuda)
        std::printf("    GPU memory free before the first call %.1f GB, after it %.1f GB\n", free0,
                    double(query_device().free_memory) / 1e9);
      std::vector<double> t;
      for (int k = 0; k < reps; ++k) {
        r = Triangulation2d{};  // (the last run's result freed before the clock: not this call's)
        const auto t0 = clk::now();
        r = delaunay2d(in.pts, o);
        t.push_back(bench::ms_since(t0));
      }
      std::sort(t.begin(), t.end());
      const double med = t[t.size() / 2];
      // every distinct input point must be a vertex (cheap enough for any size)
      std::vector<char> seen(std::size_t(n), 0);
      for (std::int32_t v : r.triangles) seen[std::size_t(v)] = 1;
      std::int64_t missing = 0;
      for (std::int64_t i = 0; i < n; ++i) missing += !seen[i] && r.duplicate_of[i] < 0;
      std::string verdict = missing ? std::to_string(missing) + " points missing" : "all points";
      if (check) {
        const auto rep =
            verify::check_delaunay2d(&in.pts.data()->x, n, r.triangles.data(),
                                     std::int64_t(r.num_triangles), r.duplicate_of.data());
        verdict += rep.ok ? ", valid" : ", INVALID: " + rep.message;
      }
      if (sample > 0) verdict += ", " + sample_check(in.pts, r, sample);
      double dev = -1;
      if (b == Backend::Cuda) {
        try {  // (the points on the device besides the library's arrays: may not fit)
          dev = bench::device_resident_ms(
              in.pts, reps, [&](const double* d, std::int64_t n) { delaunay2d_device(d, n, o); });
        } catch (const Error& e) {
          std::printf("    device-resident entry refused: %s\n", e.what());
        }
      }
      std::printf("%-22s %10lld %-5s %10.1f %9.1f %9.1f %9.1f %9.1f %9.1f %7lld %7lld %9.1f %s\n",
                  in.name.c_str(), (long long)n, backend_name(b), med, dev,
                  bench::phase_ms(r.stats, "prepare"), bench::phase_ms(r.stats, "insert"),
                  bench::phase_ms(r.stats, "output"), n / med / 1e3, (long long)r.stats.batches,
                  (long long)r.stats.flip_rounds, cg, verdict.c_str());
      std::printf(
          "    flips %lld, rounds in a team %lld, exact-list rest passes %lld, relocations for a "
          "full log %lld, rounds flipped in parts %lld, device peak %.1f B a point\n",
          (long long)r.stats.flips, (long long)r.stats.team_flip_rounds,
          (long long)r.stats.exact_rest_passes, (long long)r.stats.log_relocations,
          (long long)r.stats.split_flip_rounds, double(r.stats.device_peak_bytes) / double(n));
      if (!digital.empty())
        digital_rows(in.name, in.pts, b, reps, digital, r, &f, b == Backend::Cuda ? gpu : "cpu");
      if (voronoi) {  // the Voronoi diagram of the result: host threads, and on the executor
        std::vector<double> th;
        Voronoi2dOptions on_host;
        on_host.backend = Backend::Cpu;
        for (int k = 0; k < reps; ++k) {
          const auto t0 = clk::now();
          const Voronoi2d v = voronoi2d(&in.pts.data()->x, n, r, on_host);
          th.push_back(bench::ms_since(t0));
        }
        std::sort(th.begin(), th.end());
        const double vd = voronoi_device_ms(in.pts, b, reps);
        std::printf(
            "    voronoi: host %.1f ms, device entry %.1f ms (from a device triangulation)\n",
            th[th.size() / 2], vd);
      }
      if (b == Backend::Cuda)
        std::printf("    upload %.1f ms, copy back %.1f ms, bus floor %.1f ms\n",
                    bench::phase_ms(r.stats, "upload"), bench::phase_ms(r.stats, "copy_back"),
                    bench::bus_floor_ms(16.0 * n + 4.0 * (6.0 * r.num_triangles + n)));
      for (auto& ph : r.stats.phase_ms)
        if (ph.first.rfind("insert/", 0) == 0)
          std::printf("    %-28s %8.2f ms\n", ph.first.c_str(), ph.second);
      if (std::getenv("GPUGEOM_PROFILE")) {
        for (auto& c : r.stats.counter_map())
          std::printf(" %s=%lld", c.first.c_str(), (long long)c.second);
        for (auto& ph : r.stats.phase_ms)
          if (ph.first.rfind("insert/", 0) != 0)
            std::printf(" %s=%.2fms", ph.first.c_str(), ph.second);
        std::printf("\n");
      }
      std::fflush(stdout);
      if (f)
        f << "delaunay2d," << in.name << "," << n << "," << backend_name(b) << ","
          << (b == Backend::Cuda ? gpu : "cpu") << ",0," << med << ",0," << (dev > 0 ? dev : 0)
          << "," << med << "," << double(r.stats.exact_predicates) / std::max<double>(1, n) << "\n";
    }
    if (f && cg >= 0)
      f << "delaunay2d," << in.name << "," << n << ",cgal,cpu-1core,0," << cg << ",0,0," << cg
        << ",0\n";
  }
  return 0;
}
