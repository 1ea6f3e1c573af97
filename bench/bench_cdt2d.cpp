// gpugeom_bench_cdt2d: 2D constrained Delaunay end to end (host points and segments in, host
// triangles, neighbours and segment marks out), beside the plain Delaunay triangulation of the
// same points on the same backend, with CGAL's Constrained_Delaunay_triangulation_2 on one core
// in the same run (--cgal, when the build found CGAL). Inputs:
//   pslg:N      N uniform points, a tenth of them joined by segments: the edges of the tenth's
//               own Delaunay triangulation, each kept with probability 1/3 (about N/10
//               segments that cross nothing, each a few triangles of the whole set long);
//   P.npy:S.npy points and segments from files (bench/terrain_contours.py --segments: contour
//               lines, every edge a segment).
// --save DIR writes each input as DIR/NAME_points.npy and DIR/NAME_segments.npy for the
// Triangle anchor (bench/anchor_cdt2d.py). --check runs the exact checker (inputs up to
// --check-max points).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_csv.hpp"
#include "device_timing.hpp"
#include "gpugeom/cdt2d.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/io.hpp"
#include "verify.hpp"

#ifdef GG_BENCH_CGAL
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#endif

using namespace gpugeom;

namespace {
using clk = std::chrono::steady_clock;

struct Input {
  std::string name;
  std::vector<double> xy;
  std::vector<std::int32_t> segs;
  std::int64_t n() const { return std::int64_t(xy.size() / 2); }
  std::int64_t m() const { return std::int64_t(segs.size() / 2); }
};

Input random_pslg(std::int64_t n, Backend b) {
  Input in{"pslg", {}, {}};
  const auto p = generate2d("uniform", n, 7);
  in.xy.resize(2 * std::size_t(n));
  std::memcpy(in.xy.data(), p.data(), in.xy.size() * sizeof(double));
  // The first tenth of the points (uniform, in random order) and its Delaunay edges.
  const std::int64_t k = std::max<std::int64_t>(3, n / 10);
  Delaunay2dOptions o;
  o.backend = b;
  const auto dt = delaunay2d(in.xy.data(), k, o);
  for (std::size_t i = 0; i < dt.triangles.size(); ++i) {
    if (dt.neighbors[i] >= 0 && dt.neighbors[i] < std::int32_t(i / 3)) continue;  // once each
    if (bench::hash64(i, 5) % 3) continue;
    in.segs.push_back(dt.triangles[i - i % 3 + (i % 3 + 1) % 3]);
    in.segs.push_back(dt.triangles[i - i % 3 + (i % 3 + 2) % 3]);
  }
  return in;
}

Input from_files(const std::string& pts, const std::string& segs) {
  Input in;
  in.name = pts.substr(pts.find_last_of('/') + 1);
  in.name = in.name.substr(0, in.name.find('.'));
  const io::PointSet ps = io::read_points(pts);
  if (ps.dim != 2) throw Error(ErrorCode::InvalidInput, pts + ": not 2D points");
  in.xy.assign(ps.coords.begin(), ps.coords.end());
  in.segs = io::read_segments(segs);
  return in;
}

void save(const Input& in, const std::string& dir) {
  io::PointSet ps;
  ps.dim = 2;
  ps.coords.assign(in.xy.begin(), in.xy.end());
  io::write_points(dir + "/" + in.name + "_points.npy", ps);
  io::Grid g;
  g.shape = {in.m(), 2};
  g.type = io::ScalarType::I32;
  g.data.resize(in.segs.size() * sizeof(std::int32_t));
  std::memcpy(g.data.data(), in.segs.data(), g.data.size());
  io::write_grid(dir + "/" + in.name + "_segments.npy", g);
}

double cgal_ms(const Input& in) {
#ifdef GG_BENCH_CGAL
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using CDT = CGAL::Constrained_Delaunay_triangulation_2<K>;
  std::vector<K::Point_2> p;
  p.reserve(std::size_t(in.n()));
  for (std::int64_t i = 0; i < in.n(); ++i) p.emplace_back(in.xy[2 * i], in.xy[2 * i + 1]);
  const auto t0 = clk::now();
  CDT cdt;
  // The points (spatially sorted by CGAL), then the constraints between their handles.
  std::vector<CDT::Vertex_handle> vh(p.size());
  {
    std::vector<std::size_t> order(p.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    using Map = CGAL::Pointer_property_map<K::Point_2>::type;  // index -> point
    CGAL::spatial_sort(order.begin(), order.end(),
                       CGAL::Spatial_sort_traits_adapter_2<K, Map>(CGAL::make_property_map(p)));
    CDT::Face_handle hint;
    for (std::size_t i : order) {
      vh[i] = cdt.insert(p[i], hint);
      hint = vh[i]->face();
    }
  }
  for (std::int64_t s = 0; s < in.m(); ++s) {
    const auto a = vh[std::size_t(in.segs[2 * s])], b = vh[std::size_t(in.segs[2 * s + 1])];
    if (a != b) cdt.insert_constraint(a, b);
  }
  const double ms = bench::ms_since(t0);
  if (cdt.number_of_faces() == 0) std::printf("(CGAL built no triangle)\n");
  return ms;
#else
  (void)in;
  return -1;
#endif
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
}  // namespace

int main(int argc, char** argv) {
  std::string inputs = "pslg:100000", backend = "cuda", csv, save_dir;
  int reps = 3;
  double cgal_max = 0, check_max = 2e6;
  bool check = false, enclosed = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--inputs")
      inputs = next();
    else if (a == "--backend")
      backend = next();
    else if (a == "--reps")
      reps = std::max(1, std::stoi(next()));
    else if (a == "--cgal")
      cgal_max = std::stod(next());
    else if (a == "--check")
      check = true;
    else if (a == "--enclosed")
      enclosed = true;
    else if (a == "--check-max")
      check_max = std::stod(next());
    else if (a == "--save")
      save_dir = next();
    else if (a == "--csv")
      csv = next();
    else {
      std::cerr << "usage: gpugeom_bench_cdt2d [--inputs pslg:N,P.npy:S.npy,...] [--backend "
                   "cuda|cpu] [--reps 3] [--cgal MAX_N] [--check] [--check-max N] [--save DIR] "
                   "[--csv F] [--enclosed]\n";
      return 2;
    }
  }
  const Backend b = backend == "cpu" ? Backend::Cpu : Backend::Cuda;
  const DeviceInfo dev = query_device();
  std::printf("device: %s\n", b == Backend::Cuda ? dev.name.c_str() : "CPU executor");
  std::printf("%-12s %9s %8s | %9s %9s %9s | %8s %8s %8s %8s | %6s %9s %5s %4s | %9s %6s | %s\n",
              "input", "n", "segs", "delaunay", "cdt", "cdt dev", "dt part", "segments", "to_host",
              "domain", "recov", "cavity_t", "rnds", "ant", "cgal", "x cgal", "check");
  if (!save_dir.empty() && !bench::make_save_dir(save_dir)) return 2;
  std::ofstream f = bench::open_bench_csv(csv);
  std::stringstream ss(inputs);
  for (std::string item; std::getline(ss, item, ',');) {
    Input in;
    const auto colon = item.find(':');
    if (item.rfind("pslg:", 0) == 0)
      in = random_pslg(std::int64_t(std::stod(item.substr(5))), b);
    else if (colon != std::string::npos)
      in = from_files(item.substr(0, colon), item.substr(colon + 1));
    else
      return std::cerr << "unknown input " << item << "\n", 2;
    if (item.rfind("pslg:", 0) == 0) in.name += "_" + item.substr(5);
    if (!save_dir.empty()) save(in, save_dir);
    Delaunay2dOptions dopt;
    dopt.backend = b;
    Cdt2dOptions copt;
    copt.backend = b;
    if (enclosed) copt.domain = Cdt2dOptions::Domain::Enclosed;  // (the check then skipped)
    delaunay2d(in.xy.data(), in.n(), dopt);                      // warm-up (context, pools)
    std::vector<double> tdt, tcdt, tpart, tseg, thost, tdom;
    ConstrainedTriangulation2d r;
    for (int k = 0; k < reps; ++k) {
      auto t0 = clk::now();
      const auto dt = delaunay2d(in.xy.data(), in.n(), dopt);
      tdt.push_back(bench::ms_since(t0));
      t0 = clk::now();
      r = cdt2d(in.xy.data(), in.n(), in.segs.data(), in.m(), copt);
      tcdt.push_back(bench::ms_since(t0));
      tpart.push_back(bench::phase_ms(r.stats, "delaunay"));
      tseg.push_back(bench::phase_ms(r.stats, "segments"));
      thost.push_back(bench::phase_ms(r.stats, "to_host"));
      tdom.push_back(bench::phase_ms(r.stats, "domain"));
    }
    // Device-resident: points and segments uploaded once, cdt2d_device leaving the result on
    // the device (the enclosed domain too where asked).
    double on_dev = -1;
    if (b == Backend::Cuda) {
      std::vector<unsigned char> blob(in.xy.size() * sizeof(double) +
                                      in.segs.size() * sizeof(std::int32_t));
      std::memcpy(blob.data(), in.xy.data(), in.xy.size() * sizeof(double));
      std::memcpy(blob.data() + in.xy.size() * sizeof(double), in.segs.data(),
                  in.segs.size() * sizeof(std::int32_t));
      on_dev = bench::device_resident_ms(blob.data(), blob.size(), reps, [&](const void* d) {
        const auto* p = static_cast<const double*>(d);
        const auto* sg = reinterpret_cast<const std::int32_t*>(p + in.xy.size());
        cdt2d_device(p, in.n(), sg, in.m(), copt);
      });
    }
    std::string verdict = "-";
    if (check && !enclosed && in.n() <= check_max) {
      std::vector<std::int32_t> segs;
      for (std::int64_t s = 0; s < in.m(); ++s) {
        std::int32_t a = in.segs[2 * s], c = in.segs[2 * s + 1];
        if (r.duplicate_of[a] >= 0) a = r.duplicate_of[a];
        if (r.duplicate_of[c] >= 0) c = r.duplicate_of[c];
        if (a != c) segs.insert(segs.end(), {a, c});
      }
      const auto rep = verify::check_constrained_delaunay2d(
          in.xy.data(), in.n(), r.triangles.data(), std::int64_t(r.num_triangles), segs.data(),
          std::int64_t(segs.size() / 2), r.duplicate_of.data());
      verdict = rep.ok ? "exact" : "FAILED: " + rep.message;
    }
    const double cg = in.n() <= cgal_max ? cgal_ms(in) : -1;
    const double cdt_ms = median(tcdt);
    std::printf(
        "%-12s %9lld %8lld | %9.1f %9.1f %9.1f | %8.1f %8.1f %8.1f %8.1f | %6lld %9lld %5lld "
        "%4lld | %9.0f %6.0f | %s\n",
        in.name.c_str(), (long long)in.n(), (long long)in.m(), median(tdt), cdt_ms, on_dev,
        median(tpart), median(tseg), median(thost), median(tdom),
        (long long)r.stats.segments_recovered, (long long)r.stats.cavity_triangles,
        (long long)r.stats.recovery_rounds, (long long)r.stats.cavity_antennas, cg,
        cg > 0 ? cg / cdt_ms : 0.0, verdict.c_str());
    std::fflush(stdout);
    if (f.is_open()) {
      const char* bn = b == Backend::Cuda ? "cuda" : "cpu";
      f << "cdt2d," << in.name << "," << in.n() << "," << bn << "," << dev.name << ",0,"
        << median(tseg) << "," << median(thost) << "," << on_dev << "," << cdt_ms << ",0\n";
      f << "delaunay2d_same_points," << in.name << "," << in.n() << "," << bn << "," << dev.name
        << ",0,0,0,0," << median(tdt) << ",0\n";
      if (cg > 0)
        f << "cdt2d," << in.name << "," << in.n() << ",cgal,1 core,0,0,0,0," << cg << ",0\n";
    }
  }
  return 0;
}
