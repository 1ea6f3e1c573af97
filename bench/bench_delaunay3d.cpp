// gpugeom_bench_del3d: 3D Delaunay end to end (host points in, host arrays out) on each backend,
// with CGAL's Delaunay_triangulation_3 (sequential) on the same points in the same run when
// the build found CGAL. Prints the GPU's name, the phase times, flips, failed vertices and
// splaying time next to the totals, and on the GPU the device-resident time (points uploaded
// once, result left on the device: on_dev); --check runs the exact checker on every result.
// Usage: gpugeom_bench_del3d [--check] [--cpu] [--verbose] [--reps R] [--cgal-max N]
//        [--digital G,G,...]
//                            dist:n [dist:n ...]
// (--cpu: the CPU executor too where there is a GPU; --verbose: every phase and counter;
// --cgal-max: CGAL only up to N points, default 10^7; B/pt: the device peak per point of the
// end-to-end call (the most it held at once; the CPU executor: what phase 1 holds);
// --digital: a row of the digital method (DigiDel3D) per grid side after each incremental row,
// 0 the automatic side, with its phases and whether its tetrahedra are the incremental ones)
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_csv.hpp"
#include "device_timing.hpp"
#include "gpugeom/delaunay3d.hpp"
#include "gpugeom/generate.hpp"
#include "verify.hpp"

#ifdef GG_BENCH_CGAL
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#endif
#ifdef GG_BENCH_CGAL_PAR
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Spatial_lock_grid_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_3.h>
#include <tbb/global_control.h>
#include <cstdlib>
#include <memory>
#endif

using namespace gpugeom;

namespace {
using clk = std::chrono::steady_clock;
using bench::ms_since;

// Bytes a point: the device peak where the call ran on the GPU, else phase 1's bytes.
std::int64_t bytes_per_point(const gpugeom::Delaunay3dStats& st) {
  const std::int64_t peak = st.device_peak_bytes;
  return peak > 0 ? peak : st.device_bytes_phase1;
}
double phase(const RunStats& s, const char* name) {
  return bench::phase_ms(s, name);
}

// The median of reps end-to-end runs with options o, and the last run's result.
double median_run(const std::vector<Point3>& pts, const Delaunay3dOptions& o, int reps,
                  Triangulation3d& t) {
  std::vector<double> ms;
  for (int r = 0; r < reps; ++r) {
    t = Triangulation3d{};  // (the last run's result freed before the clock: not this call's work)
    const auto t0 = clk::now();
    t = delaunay3d(pts, o);
    ms.push_back(ms_since(t0));
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

#ifdef GG_BENCH_CGAL
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
std::vector<K::Point_3> to_cgal(const std::vector<Point3>& p) {
  std::vector<K::Point_3> in;
  in.reserve(p.size());
  for (auto& q : p) in.emplace_back(q.x, q.y, q.z);
  return in;
}
#endif

double cgal_ms(const std::vector<Point3>& p, std::int64_t& cells) {
#ifdef GG_BENCH_CGAL
  const std::vector<K::Point_3> in = to_cgal(p);
  const auto t0 = clk::now();
  CGAL::Delaunay_triangulation_3<K> dt(in.begin(), in.end());
  const double ms = ms_since(t0);
  cells = std::int64_t(dt.number_of_finite_cells());
  return ms;
#else
  (void)p;
  cells = -1;
  return -1;
#endif
}
// CGAL's parallel construction (TBB; its documented set-up: a parallel data structure and a grid
// of locks over the points' box), -1 where the build has no TBB. On OMP_NUM_THREADS threads
// where that is set, as the CPU executor (bench/cpu_scaling.sh compares the two at each count),
// else on every host core.
double cgal_par_ms(const std::vector<Point3>& p) {
#ifdef GG_BENCH_CGAL_PAR
  std::unique_ptr<tbb::global_control> limit;
  if (const char* e = std::getenv("OMP_NUM_THREADS"); e && std::atoi(e) > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  std::size_t(std::atoi(e)));
  using Tds = CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_3<K>,
                                                   CGAL::Delaunay_triangulation_cell_base_3<K>,
                                                   CGAL::Parallel_tag>;
  using PDT = CGAL::Delaunay_triangulation_3<K, Tds>;
  const std::vector<K::Point_3> in = to_cgal(p);
  const auto t0 = clk::now();
  PDT::Lock_data_structure locks(CGAL::bbox_3(in.begin(), in.end()), 50);
  PDT dt(in.begin(), in.end(), &locks);
  return ms_since(t0);
#else
  (void)p;
  return -1;
#endif
}
// The tetrahedra as sorted rows, sorted: to compare two methods' results.
std::vector<std::array<std::int32_t, 4>> tet_rows(const Triangulation3d& t) {
  std::vector<std::array<std::int32_t, 4>> r(t.tetrahedra.size() / 4);
  for (std::size_t c = 0; c < r.size(); ++c) {
    for (int k = 0; k < 4; ++k) r[c][std::size_t(k)] = t.tetrahedra[4 * c + std::size_t(k)];
    std::sort(r[c].begin(), r[c].end());
  }
  std::sort(r.begin(), r.end());
  return r;
}
}  // namespace

int run(int argc, char** argv) {
  bool check = false, with_cpu = false;
  int reps = 3;
  bool verbose = false;  // every phase and counter of the last run, after its row
  std::int64_t cgal_max = 10'000'000;
  std::vector<std::string> jobs;
  std::vector<std::int64_t> digital;  // grid sides of the digital rows (0: automatic)
  std::string csv;                    // rows appended for bench/plot.py and the docs' plots
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--check")
      check = true;
    else if (a == "--cpu")
      with_cpu = true;
    else if (a == "--verbose")
      verbose = true;
    else if (a == "--reps" && i + 1 < argc)
      reps = std::atoi(argv[++i]);
    else if (a == "--csv" && i + 1 < argc)
      csv = argv[++i];
    else if (a == "--cgal-max" && i + 1 < argc)
      cgal_max = std::int64_t(std::atof(argv[++i]));
    else if (a == "--digital" && i + 1 < argc)
      for (std::string rest = argv[++i]; !rest.empty();) {
        const auto comma = rest.find(',');
        digital.push_back(std::atoll(rest.substr(0, comma).c_str()));
        rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
      }
    else
      jobs.push_back(a);
  }
  const DeviceInfo dev = query_device();
  std::printf("# device: %s\n", dev.available ? dev.name.c_str() : "none");
  std::ofstream f = bench::open_bench_csv(csv);
  std::printf("%-12s %9s %-5s %10s %8s %8s %8s %8s %9s %8s %7s %10s %6s %9s %9s %6s\n", "dist", "n",
              "back", "total_ms", "on_dev", "prep", "ins+flip", "splay", "flips", "failed", "stars",
              "tets", "B/pt", "cgal_ms", "cgal_par", "check");
  for (const std::string& job : jobs) {
    const auto colon = job.find(':');
    const std::string dist = job.substr(0, colon);
    const std::int64_t n = std::int64_t(std::atof(job.c_str() + colon + 1));
    const auto pts = generate3d(dist, n, 7);
    std::int64_t cells = 0;
    const double cg = n <= cgal_max ? cgal_ms(pts, cells) : -1;
    const double cgp = n <= cgal_max ? cgal_par_ms(pts) : -1;
    if (f && cg >= 0)
      f << "delaunay3d," << dist << "," << n << ",cgal,cpu-1core,0," << cg << ",0,0," << cg
        << ",0\n";
    if (f && cgp >= 0)
      f << "delaunay3d," << dist << "," << n << ",cgal-parallel,cpu-all-cores,0," << cgp << ",0,0,"
        << cgp << ",0\n";
    for (Backend b : {Backend::Cuda, Backend::Cpu}) {
      if (b == Backend::Cuda && !dev.available) continue;
      if (b == Backend::Cpu && !with_cpu && dev.available) continue;
      Delaunay3dOptions o;
      o.backend = b;
      Triangulation3d t;
      const double total = median_run(pts, o, reps, t);
      // Device-resident: points uploaded once, the result left on the GPU.
      const double on_dev =
          b == Backend::Cuda
              ? bench::device_resident_ms(
                    pts, reps, [](const double* d, std::int64_t k) { delaunay3d_device(d, k); })
              : -1;
      std::string ok = "-";
      if (check) {
        auto rep = verify::check_delaunay3d(&pts.data()->x, n, t.tetrahedra.data(),
                                            std::int64_t(t.num_tetrahedra), t.duplicate_of.data());
        ok = rep.ok ? "ok" : "FAIL";
        if (!rep.ok) std::printf("# %s\n", rep.message.c_str());
      }
      std::printf(
          "%-12s %9lld %-5s %10.1f %8.1f %8.1f %8.1f %8.1f %9lld %8lld %7lld %10zu %6lld %9.1f "
          "%9.1f %6s\n",
          dist.c_str(), (long long)n, b == Backend::Cuda ? "cuda" : "cpu", total, on_dev,
          phase(t.stats, "prepare"), phase(t.stats, "insert_flip"), phase(t.stats, "splay"),
          (long long)(t.stats.flips23 + t.stats.flips32), (long long)t.stats.failed_vertices,
          (long long)t.stats.stars_built, t.num_tetrahedra,
          (long long)(bytes_per_point(t.stats) / std::max<std::int64_t>(n, 1)), cg, cgp,
          ok.c_str());
      if (b == Backend::Cuda)  // points in; the five arrays out
        std::printf("#   bus floor %.1f ms\n",
                    bench::bus_floor_ms(24.0 * n + 4.0 * (8.0 * t.num_tetrahedra + 2.0 * n +
                                                          3.0 * t.num_hull_facets)));
      if (verbose) bench::print_stats_lines(t.stats);
      std::fflush(stdout);
      if (f)
        f << "delaunay3d," << dist << "," << n << "," << backend_name(b) << ","
          << (b == Backend::Cuda ? dev.name : std::string("cpu")) << ",0," << total << ",0,"
          << (on_dev > 0 ? on_dev : 0) << "," << total << ",0\n";
      for (const std::int64_t g : digital) {
        Delaunay3dOptions od = o;
        od.method = Method::Digital;
        od.grid = g;
        Triangulation3d d;
        const double dt = median_run(pts, od, reps, d);
        const double d_on_dev =
            b == Backend::Cuda ? bench::device_resident_ms(pts, reps,
                                                           [&](const double* x, std::int64_t k) {
                                                             delaunay3d_device(x, k, od);
                                                           })
                               : -1;
        const bool same = tet_rows(d) == tet_rows(t);
        std::printf(
            "%-12s %9lld %-5s %10.1f %8.1f   digital grid %4lld: voronoi %.1f sets %.1f stars "
            "%.1f splay %.1f (%lld rounds, %lld insertions, %lld growths) tets %.1f; "
            "dig/incr %.2fx, cgal/dig %.1fx, %s\n",
            dist.c_str(), (long long)n, b == Backend::Cuda ? "cuda" : "cpu", dt, d_on_dev,
            (long long)d.stats.digital_grid,
            phase(d.stats, "digital_grid") + phase(d.stats, "digital_pba"),
            phase(d.stats, "digital_working_sets"), phase(d.stats, "digital_stars"),
            phase(d.stats, "digital_splay"), (long long)d.stats.digital_splay_rounds,
            (long long)d.stats.digital_star_insertions, (long long)d.stats.digital_star_growths,
            phase(d.stats, "digital_tetrahedra"), dt / total, cg > 0 ? cg / dt : -1.0,
            same ? "identical" : "DIFFERENT");
        if (verbose) bench::print_stats_lines(d.stats);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const gpugeom::Error& e) {  // a bad job (unknown distribution, bad size) or input
    std::fprintf(stderr, "gpugeom_bench_del3d: %s: %s\n", gpugeom::error_code_name(e.code()),
                 e.what());
    return 2;
  }
}
