// gpugeom_bench_dynamic: triangulations that follow their points (issue 47). For each
// dist:n:k, k of n points inserted into the triangulation of the other n - k, timed beside a
// fresh triangulation of all n in the same run:
//   fresh e2e   delaunay2d on the n host points, host arrays out
//   fresh dev   delaunay2d_device on the n points already on the device
//   insert      DynamicDelaunay2d::insert of the k host points (the state brought up to date on
//               the executor; the object built beforehand, untimed)
//   insert e2e  the same plus triangulation() (the caller's host arrays out)
//   insert dev  insert_device of the k points already on the device (from_device beforehand)
// Medians of --reps runs; the last insert's phases are printed, and the result is checked
// against the fresh one (the same triangles).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "bench_csv.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/generate.hpp"
#include "verify.hpp"
#include <memory>

#ifdef GPUGEOM_HAVE_CUDA
#include <cuda_runtime.h>
#endif

using namespace gpugeom;

namespace {
using clk = std::chrono::steady_clock;

// Median of reps timings of run(); prepare() runs untimed before each.
double median_ms(int reps, const std::function<void()>& prepare, const std::function<void()>& run) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    prepare();
    const auto t0 = clk::now();
    run();
    t.push_back(bench::ms_since(t0));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

void print_phases(const Stats& s) {
  std::printf("    insert phases:");
  for (const auto& [name, ms] : s.phase_ms) std::printf(" %s %.2f", name.c_str(), ms);
  for (const char* c : {"inserted_points", "batches", "flips", "flip_rounds", "start_walk_steps"}) {
    const auto it = s.counters.find(c);
    if (it != s.counters.end()) std::printf(" | %s %lld", c, (long long)it->second);
  }
  std::printf("\n");
}

struct Row {
  std::string dist;
  std::int64_t n = 0, k = 0;
};

Row parse(const std::string& s) {
  Row r;
  const auto a = s.find(':'), b = s.rfind(':');
  if (a == std::string::npos || a == b) {
    std::fprintf(stderr, "expected dist:n:k, got %s\n", s.c_str());
    std::exit(2);
  }
  r.dist = s.substr(0, a);
  r.n = std::int64_t(std::stod(s.substr(a + 1, b - a - 1)));
  r.k = std::int64_t(std::stod(s.substr(b + 1)));
  return r;
}

void run_row(const Row& row, Backend b, int reps) {
  const auto p = generate2d(row.dist, row.n, 7);
  const std::int64_t n = std::int64_t(p.size()), k = std::min(row.k, n - 3), base = n - k;
  Delaunay2dOptions o;
  o.backend = b;
  Triangulation2d fresh;
  const double fresh_e2e = median_ms(
      reps, [] {}, [&] { fresh = delaunay2d(p, o); });
  std::unique_ptr<DynamicDelaunay2d> d;
  const double ins = median_ms(
      reps, [&] { d = std::make_unique<DynamicDelaunay2d>(&p.data()->x, base, o); },
      [&] { d->insert(&p[std::size_t(base)].x, k); });
  print_phases(d->stats());
  Triangulation2d got;
  const double ins_e2e = median_ms(
      reps, [&] { d = std::make_unique<DynamicDelaunay2d>(&p.data()->x, base, o); },
      [&] {
        d->insert(&p[std::size_t(base)].x, k);
        got = d->triangulation();
      });
  const bool same = verify::canonical_triangles(got.triangles.data(), got.triangle_count) ==
                    verify::canonical_triangles(fresh.triangles.data(), fresh.triangle_count);
  double fresh_dev = -1, ins_dev = -1;
#ifdef GPUGEOM_HAVE_CUDA
  if (b == Backend::Cuda) {
    double* dp = nullptr;
    const std::size_t bytes = p.size() * sizeof(Point2);
    if (cudaMalloc(&dp, bytes) == cudaSuccess &&
        cudaMemcpy(dp, p.data(), bytes, cudaMemcpyHostToDevice) == cudaSuccess) {
      fresh_dev = median_ms(
          reps, [] {}, [&] { delaunay2d_device(dp, n, o); });
      ins_dev = median_ms(
          reps,
          [&] {
            d = std::make_unique<DynamicDelaunay2d>(DynamicDelaunay2d::from_device(dp, base, o));
          },
          [&] { d->insert_device(dp + 2 * base, k); });
    }
    cudaFree(dp);
  }
#endif
  std::printf(
      "%-10s %-8s n=%-10lld k=%-9lld fresh e2e %9.2f  fresh dev %9.2f  insert %9.2f  insert "
      "e2e %9.2f  insert dev %9.2f  (dev ratio %.3f)  %s\n",
      row.dist.c_str(), b == Backend::Cuda ? "cuda" : "cpu", (long long)n, (long long)k, fresh_e2e,
      fresh_dev, ins, ins_e2e, ins_dev, fresh_dev > 0 ? ins_dev / fresh_dev : ins / fresh_e2e,
      same ? "same triangles" : "DIFFERENT TRIANGLES");
  std::fflush(stdout);
}
}  // namespace

int main(int argc, char** argv) {
  int reps = 3;
  std::string which = "all";
  std::vector<Row> rows;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--reps" && i + 1 < argc)
      reps = std::max(1, std::atoi(argv[++i]));
    else if (a == "--backend" && i + 1 < argc)
      which = argv[++i];
    else
      rows.push_back(parse(a));
  }
  if (rows.empty()) rows = {{"uniform", 1000000, 1000}, {"uniform", 1000000, 100000}};
  const DeviceInfo dev = query_device();
  std::printf("gpugeom_bench_dynamic: 2D Delaunay, k of n points inserted (ms, median of %d)%s%s\n",
              reps, dev.available ? "; GPU: " : "", dev.available ? dev.name.c_str() : "");
  for (Backend b : bench::backends(which))
    for (const Row& r : rows) run_row(r, b, reps);
  return 0;
}
