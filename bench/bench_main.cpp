// gpugeom_bench: times a problem over distributions and sizes on the chosen backends and writes
// CSV rows (problem, distribution, n, backend, phases, device-resident and with-copies totals).
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "bench_csv.hpp"
#include "bench_problems.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/spatial.hpp"

using namespace gpugeom;

namespace {
std::vector<std::string> list(const std::string& s) {
  std::vector<std::string> v;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');)
    if (!x.empty()) v.push_back(x);
  return v;
}
void usage() {
  std::cout << "usage: gpugeom_bench [--problem "
               "hilbert|orient3d|insphere|orient3d-full|insphere-full] [--dim 2|3]\n"
               "                     [--dist uniform,ball,...] [--sizes 1e5,1e6] [--backend "
               "cpu|cuda|all]\n"
               "                     [--reps 5] [--seed 1] [--csv FILE]\n";
}
}  // namespace

int main(int argc, char** argv) {
  std::string problem = "hilbert", dists = "uniform", sizes = "100000,1000000", backends = "all",
              csv;
  int dim = 3, reps = 5;
  unsigned long long seed = 1;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "option " << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--problem")
      problem = next();
    else if (a == "--dim")
      dim = std::stoi(next());
    else if (a == "--dist")
      dists = next();
    else if (a == "--sizes")
      sizes = next();
    else if (a == "--backend")
      backends = next();
    else if (a == "--reps")
      reps = std::stoi(next());
    else if (a == "--seed")
      seed = std::stoull(next());
    else if (a == "--csv")
      csv = next();
    else if (a == "--help" || a == "-h")
      return usage(), 0;
    else
      return usage(), 2;
  }
  std::vector<Backend> bks;
  for (auto& b : list(backends == "all" ? "cpu,cuda" : backends)) {
    Backend k = parse_backend(b);
    if (k == Backend::Cuda && !query_device().available) {
      std::cerr << "note: CUDA backend skipped (" << query_device().reason << ")\n";
      continue;
    }
    bks.push_back(k);
  }
  std::string gpu = query_device().available ? query_device().name : "none";
  std::ofstream f = bench::open_bench_csv(csv);
  // exact%: items the filter left to the exact stages; last%: of all items, those the middle
  // tier left to the full expansion (three-tier predicate problems only)
  std::printf("%-13s %-12s %10s %-5s %10s %10s %12s %8s %8s\n", "problem", "dist", "n", "bk",
              "compute", "w/copies", "Mitems/s", "exact%", "last%");
  for (auto& d : list(dists))
    for (auto& s : list(sizes)) {
      const long long n = (long long)std::stod(s);
      bench::ProblemInput in;
      in.problem = problem;
      in.dim = dim;
      in.reps = reps;
      if (dim == 2) {
        auto p = generate2d(d, n, seed);
        in.coords.assign(&p.data()->x, &p.data()->x + 2 * p.size());
      } else {
        auto p = generate3d(d, n, seed);
        if (problem != "hilbert") {  // predicates run on spatially sorted points, as algorithms do
          auto o = hilbert_order(p, Backend::Cpu);
          std::vector<Point3> q(p.size());
          for (std::size_t i = 0; i < o.size(); ++i) q[i] = p[o[i]];
          p.swap(q);
        }
        in.coords.assign(&p.data()->x, &p.data()->x + 3 * p.size());
      }
      for (Backend b : bks) {
        bench::Phases ph = b == Backend::Cuda ?
#ifdef GPUGEOM_HAVE_CUDA
                                              bench::cuda_impl::run(in)
#else
                                              bench::Phases{}
#endif
                                              : bench::cpu_impl::run(in);
        const double resident = ph["compute"],
                     total = ph["upload"] + ph["compute"] + ph["download"];
        const double exact = ph.count("exact_fraction") ? ph["exact_fraction"] : 0.0;
        const double last = ph.count("last_fraction") ? ph["last_fraction"] : 0.0;
        std::printf("%-13s %-12s %10lld %-5s %10.3f %10.3f %12.1f %8.4f %8.4f\n", problem.c_str(),
                    (d + (dim == 2 ? "2d" : "3d")).c_str(), n, backend_name(b), resident, total,
                    n / resident / 1e3, 100 * exact, 100 * last);
        if (f)
          f << problem << "," << d << (dim == 2 ? "2d" : "3d") << "," << n << "," << backend_name(b)
            << "," << (b == Backend::Cuda ? gpu : std::string("cpu")) << "," << ph["upload"] << ","
            << ph["compute"] << "," << ph["download"] << "," << resident << "," << total << ","
            << exact << "\n";
      }
    }
  return 0;
}
