// gpugeom_bench_memory: the device memory each capability needs per element (issue 23), from
// RunStats::device_peak_bytes (the device pool's peak during the call, exec/peak.hpp), host
// arrays in and out. Rows: capability, input, n (points or voxels), peak MB, bytes per element.
//
//   gpugeom_bench_memory [--sizes 1e6,1e7] [--grids 2048,8192] [--volumes 256,512]
//                        [--only delaunay2d,hull3d,delaunay3d,edt]
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "gpugeom/gpugeom.hpp"

using namespace gpugeom;

namespace {

std::vector<double> numbers(const std::string& s) {
  std::vector<double> v;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');)
    if (!x.empty()) v.push_back(std::stod(x));
  return v;
}

void row(const char* what, const char* input, std::int64_t n, const RunStats& st) {
  const double b = st.device_peak_bytes ? double(st.device_peak_bytes) : -1;
  std::printf("%-12s %-18s %12lld %10.1f MB %8.1f B/element\n", what, input, (long long)n, b / 1e6,
              b / double(n));
  std::fflush(stdout);
}

// A grid with one site per 1000 voxels (a few thousand sites: the PBA passes' general case).
std::vector<std::uint8_t> sparse_sites(std::int64_t count) {
  std::vector<std::uint8_t> g(std::size_t(count), 0);
  std::mt19937_64 rng(3);
  for (std::int64_t k = 0; k < count / 1000 + 1; ++k) g[rng() % std::uint64_t(count)] = 1;
  return g;
}

}  // namespace

int main(int argc, char** argv) {
  std::string sizes = "1e6,1e7", grids = "2048,8192", volumes = "256,512",
              only = "delaunay2d,hull3d,delaunay3d,edt";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--sizes")
      sizes = v;
    else if (k == "--grids")
      grids = v;
    else if (k == "--volumes")
      volumes = v;
    else if (k == "--only")
      only = v;
  }
  const DeviceInfo d = query_device();
  if (!d.available) {
    std::printf("no usable GPU: %s\n", d.reason.c_str());
    return 77;
  }
  std::printf("GPU: %s\n", d.name.c_str());
  auto want = [&](const char* w) {
    return ("," + only + ",").find("," + std::string(w) + ",") != std::string::npos;
  };
  for (double nn : numbers(sizes)) {
    const auto n = std::int64_t(nn);
    Delaunay2dOptions o2;
    o2.backend = Backend::Cuda;
    if (want("delaunay2d"))
      row("delaunay2d", "uniform", n, delaunay2d(generate2d("uniform", n, 1), o2).stats);
    Hull3dOptions oh;
    oh.backend = Backend::Cuda;
    if (want("hull3d")) {
      row("hull3d", "ball", n, convex_hull3d(generate3d("ball", n, 1), oh).stats);
      row("hull3d", "sphere", n, convex_hull3d(generate3d("sphere", n, 1), oh).stats);
    }
    Delaunay3dOptions o3;
    o3.backend = Backend::Cuda;
    if (want("delaunay3d"))
      row("delaunay3d", "uniform", n, delaunay3d(generate3d("uniform", n, 1), o3).stats);
  }
  EdtOptions oe;
  oe.backend = Backend::Cuda;
  oe.distance = 32;
  for (double g : want("edt") ? numbers(grids) : std::vector<double>{}) {
    const auto s = std::int64_t(g);
    const auto img = sparse_sites(s * s);
    GridView v{img.data(), io::ScalarType::U8, {s, s}};
    row("edt", "2D, float32 out", s * s, distance_transform(v, SiteRule::NonZero, oe).stats);
    EdtOptions of = oe;
    of.features = true;
    row("edt", "2D, + features", s * s, distance_transform(v, SiteRule::NonZero, of).stats);
  }
  for (double g : want("edt") ? numbers(volumes) : std::vector<double>{}) {
    const auto s = std::int64_t(g);
    const auto vol = sparse_sites(s * s * s);
    GridView v{vol.data(), io::ScalarType::U8, {s, s, s}};
    row("edt", "3D, float32 out", s * s * s, distance_transform(v, SiteRule::NonZero, oe).stats);
    EdtOptions ol = oe;
    ol.labels = true;
    row("edt", "3D, + labels", s * s * s, distance_transform(v, SiteRule::NonZero, ol).stats);
  }
  return 0;
}
