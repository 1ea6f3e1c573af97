// gpugeom_bench_cvd: time per weighted Lloyd iteration (PBA Voronoi diagram + every cell's
// weighted centroid + the moves, with the one scalar copy back) over grid sizes and site
// counts on each backend. The density is a smooth ramp times hashed noise in [0.25, 1].
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "bench_csv.hpp"
#include "device_timing.hpp"
#include "gpugeom/cvd.hpp"
#include "gpugeom/io.hpp"

using namespace gpugeom;

namespace {
io::Grid density(const std::vector<std::int64_t>& shape) {
  io::Grid g;
  g.shape = shape;
  g.type = io::ScalarType::F32;
  g.data.resize(std::size_t(g.count()) * 4);
  const std::int64_t cols = shape.back();
#pragma omp parallel for
  for (std::int64_t i = 0; i < g.count(); ++i) {
    const double noise = double(bench::hash64(std::uint64_t(i), 0) >> 11) / 9007199254740992.0;
    const float v = float((0.25 + 0.75 * double(i % cols) / cols) * (0.5 + 0.5 * noise));
    std::memcpy(&g.data[std::size_t(i) * 4], &v, 4);
  }
  return g;
}
}  // namespace

int main(int argc, char** argv) {
  std::string sides = "1024", sites = "1000", backends = "all", csv;
  int dim = 2, iters = 10;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--dim")
      dim = std::stoi(next());
    else if (a == "--sides")
      sides = next();
    else if (a == "--sites")
      sites = next();
    else if (a == "--backend")
      backends = next();
    else if (a == "--iters")
      iters = std::stoi(next());
    else if (a == "--csv")
      csv = next();
    else {
      std::cout << "usage: gpugeom_bench_cvd [--dim 2|3] [--sides 1024,4096] [--sites 1e3,1e5] "
                   "[--backend cpu|cuda|all] [--iters 10] [--csv FILE]\n";
      return a == "--help" ? 0 : 2;
    }
  }
  const std::vector<Backend> bks = bench::backends(backends);
  const std::string gpu = query_device().available ? query_device().name : "none";
  std::ofstream f = bench::open_bench_csv(csv);
  std::printf("%-4s %-16s %9s %-5s %8s %12s %10s %12s %10s %10s %9s\n", "cvd", "grid", "sites",
              "bk", "iters", "ms/iter", "setup", "energy drop", "total ms", "on_dev ms",
              "bus_floor");
  for (double side : bench::numbers(sides)) {
    const std::vector<std::int64_t> shape(dim, std::int64_t(side));
    const io::Grid g = density(shape);
    for (double ns : bench::numbers(sites)) {
      if (ns >= std::pow(side, dim) / 4) continue;
      for (Backend b : bks) {
        CvdOptions o;
        o.backend = b;
        o.num_sites = std::int64_t(ns);
        o.max_iterations = 2;  // warm-up
        o.move_tolerance = 0;
        centroidal_voronoi(g, o);
        o.max_iterations = iters;
        const auto t0 = std::chrono::steady_clock::now();
        const CvdResult r = centroidal_voronoi(g, o);
        const double total = bench::ms_since(t0);
        // The same call with the density already on the device (the sites left there).
        const double on_dev = b == Backend::Cuda
                                  ? bench::device_resident_ms(g.data.data(), g.data.size(), 3,
                                                              [&](const void* d) {
                                                                GridView v;
                                                                v.data = d;
                                                                v.type = g.type;
                                                                v.shape = g.shape;
                                                                centroidal_voronoi_device(v, o);
                                                              })
                                  : -1;
        const double floor_ms = bench::bus_floor_ms(double(g.data.size()) + 8.0 * (dim + 1) * ns);
        const double per = bench::phase_ms(r.stats, "iterations") / r.iterations;
        const std::string grid =
            dim == 2 ? std::to_string(shape[0]) + "^2" : std::to_string(shape[0]) + "^3";
        std::printf("%-4s %-16s %9lld %-5s %8d %12.3f %10.1f %11.1f%% %10.1f %10.1f %9.2f\n", "cvd",
                    grid.c_str(), (long long)ns, backend_name(b), r.iterations, per,
                    bench::phase_ms(r.stats, "setup"),
                    100 * (1 - r.energy.back() / r.energy.front()), total, on_dev, floor_ms);
        if (f)
          f << "cvd_iteration," << grid << "_" << (long long)ns << "sites," << (long long)ns << ","
            << backend_name(b) << "," << (b == Backend::Cuda ? gpu : "cpu") << ",0," << per << ",0,"
            << per << "," << per << ",0\n";
      }
    }
  }
  return 0;
}
