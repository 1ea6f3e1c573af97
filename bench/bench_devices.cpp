// gpugeom_bench_devices: delaunay3d_devices / delaunay2d_devices (one block per listed device)
// beside one delaunay3d / delaunay2d call on the same points, end to end (the caller's host
// points in, host arrays out: the several-device entries have no device-resident form), best of
// --reps runs; checks that the arrays are equal. Usage:
//   gpugeom_bench_devices DIM N DIST BACKEND DEVICES... (DEVICES: comma lists, e.g. 0 0,0 0,1)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/multi_gpu.hpp"

using namespace gpugeom;

namespace {

double ms_now() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

std::vector<int> parse(const std::string& s) {
  std::vector<int> out;
  std::stringstream in(s);
  std::string x;
  while (std::getline(in, x, ',')) out.push_back(std::atoi(x.c_str()));
  return out;
}

// The simplices of either result, for the check that the arrays are the single call's.
const HostVector<std::int32_t>& rows_of(const Triangulation2d& t) {
  return t.triangles;
}
const HostVector<std::int32_t>& rows_of(const Triangulation3d& t) {
  return t.tetrahedra;
}

template <class F>
double best(int reps, F&& f) {
  double b = 1e300;
  for (int r = 0; r < reps; ++r) {
    const double t = ms_now();
    f();
    b = std::min(b, ms_now() - t);
  }
  return b;
}

template <class Opt, class Single, class Devices>
void run(const double* p, std::int64_t n, Backend backend, const std::vector<std::string>& lists,
         int reps, const char* what, Single single, Devices devices) {
  Opt o;
  o.backend = backend;
  auto want = single(p, n, o);
  const double t1 = best(reps, [&] { want = single(p, n, o); });
  std::printf("%s n=%lld single %.1f ms\n", what, (long long)n, t1);
  for (const auto& l : lists) {
    auto got = devices(p, n, parse(l), o);
    const double tk = best(reps, [&] { got = devices(p, n, parse(l), o); });
    const bool same = rows_of(got) == rows_of(want) && got.neighbors == want.neighbors &&
                      got.duplicate_of == want.duplicate_of;
    std::printf(
        "%s n=%lld devices [%s] %.1f ms (%.2fx of single) second rounds %lld/%lld, "
        "local points/point %.3f, same arrays %s |",
        what, (long long)n, l.c_str(), tk, tk / t1, (long long)got.stats.blocks_second_round,
        (long long)got.stats.blocks, double(got.stats.block_local_points) / double(n),
        same ? "yes" : "NO");
    for (auto& [name, ms] : got.stats.phase_ms) std::printf(" %s=%.0f", name.c_str(), ms);
    std::printf("\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: %s DIM N DIST cpu|cuda DEVICES... [--reps K]\n", argv[0]);
    return 2;
  }
  const int dim = std::atoi(argv[1]);
  const std::int64_t n = std::int64_t(std::atof(argv[2]));  // (1e7 as 10000000)
  const std::string dist = argv[3];
  const Backend backend = std::string(argv[4]) == "cpu" ? Backend::Cpu : Backend::Cuda;
  std::vector<std::string> lists;
  int reps = 2;
  for (int i = 5; i < argc; ++i) {
    if (std::string(argv[i]) == "--reps" && i + 1 < argc)
      reps = std::atoi(argv[++i]);
    else
      lists.push_back(argv[i]);
  }
  const DeviceInfo d = query_device();
  std::printf("device: %s\n", backend == Backend::Cuda ? d.name.c_str() : "CPU executor");
  if (dim == 2) {
    const auto pts = generate2d(dist, n, 1);
    run<Delaunay2dOptions>(
        &pts.data()->x, n, backend, lists, reps, ("2D " + dist).c_str(),
        [](const double* p, std::int64_t k, const Delaunay2dOptions& o) {
          return delaunay2d(p, k, o);
        },
        [](const double* p, std::int64_t k, const std::vector<int>& v, const Delaunay2dOptions& o) {
          return delaunay2d_devices(p, k, v, o);
        });
  } else {
    const auto pts = generate3d(dist, n, 1);
    run<Delaunay3dOptions>(
        &pts.data()->x, n, backend, lists, reps, ("3D " + dist).c_str(),
        [](const double* p, std::int64_t k, const Delaunay3dOptions& o) {
          return delaunay3d(p, k, o);
        },
        [](const double* p, std::int64_t k, const std::vector<int>& v, const Delaunay3dOptions& o) {
          return delaunay3d_devices(p, k, v, o);
        });
  }
  return 0;
}
