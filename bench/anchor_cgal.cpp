// CGAL anchors, timed on the same generated points as gpugeom's benchmarks (one CPU core, exact
// predicates kernel): 2D/3D Delaunay triangulation and the 3D convex hull; and for issue 47's
// triangulations that follow their points (the points of gpugeom_bench_dynamic: --seed 7),
// CGAL's own updates of a kept triangulation (the build before them untimed): insert2d/insert3d
// (the last --k of the n points inserted as one range, which CGAL sorts spatially),
// move2d/move3d (every vertex moved with Delaunay_triangulation::move to the points displaced by
// --move times the mean spacing, bench/displace.hpp) and remove2d/remove3d (--k vertices, the
// benchmark's choice, removed one by one).
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/convex_hull_3.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "displace.hpp"
#include "gpugeom/generate.hpp"

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

namespace {
// Kept triangulations with each vertex's input index.
using DT2 = CGAL::Delaunay_triangulation_2<
    K, CGAL::Triangulation_data_structure_2<CGAL::Triangulation_vertex_base_with_info_2<int, K>>>;
using DT3 = CGAL::Delaunay_triangulation_3<
    K, CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_with_info_3<int, K>>>;
K::Point_2 cgal_point(const gpugeom::Point2& p) {
  return {p.x, p.y};
}
K::Point_3 cgal_point(const gpugeom::Point3& p) {
  return {p.x, p.y, p.z};
}

// One update of a kept triangulation (what: insert, move, remove), timed; returns the ms and
// the finite simplices after it in out.
template <class DT, int dim, class P>
double update(const std::string& what, const std::vector<P>& p, long long k, double f,
              std::size_t& out) {
  using Point = typename DT::Point;
  std::vector<std::pair<Point, int>> all;
  for (std::size_t i = 0; i < p.size(); ++i) all.emplace_back(cgal_point(p[i]), int(i));
  const std::size_t base = what == "insert" ? p.size() - std::size_t(k) : p.size();
  DT dt(all.begin(), all.begin() + std::ptrdiff_t(base));
  std::vector<typename DT::Vertex_handle> h(p.size());
  for (auto v : dt.finite_vertex_handles()) h[std::size_t(v->info())] = v;
  std::vector<Point> q;
  if (what == "move")
    for (const auto& x : gpugeom::bench::displaced<dim>(p, f)) q.push_back(cgal_point(x));
  const std::vector<std::int32_t> idx =
      what == "remove" ? gpugeom::bench::removal_choice(std::int64_t(p.size()), k)
                       : std::vector<std::int32_t>();
  const auto t0 = std::chrono::steady_clock::now();
  if (what == "insert") dt.insert(all.begin() + std::ptrdiff_t(base), all.end());
  if (what == "move")
    for (std::size_t i = 0; i < h.size(); ++i) dt.move(h[i], q[i]);
  if (what == "remove")
    for (std::int32_t i : idx) dt.remove(h[std::size_t(i)]);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if constexpr (dim == 2)
    out = dt.number_of_faces();
  else
    out = dt.number_of_finite_cells();
  return ms;
}
}  // namespace

int main(int argc, char** argv) {
  std::string problem = "delaunay2d", dists = "uniform", sizes = "100000", csv;
  unsigned long long seed = 1;
  long long k = 1000;  // insert / remove
  double move = 1e-3;  // move: the step in mean spacings
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string a = argv[i], v = argv[i + 1];
    if (a == "--problem")
      problem = v;
    else if (a == "--dist")
      dists = v;
    else if (a == "--sizes")
      sizes = v;
    else if (a == "--seed")
      seed = std::stoull(v);
    else if (a == "--csv")
      csv = v;
    else if (a == "--k")
      k = (long long)std::stod(v);
    else if (a == "--move")
      move = std::stod(v);
    else
      return std::cerr << "unknown option " << a << "\n", 2;
  }
  std::ofstream f;
  if (!csv.empty()) f.open(csv, std::ios::app);
  auto split = [](const std::string& s) {
    std::vector<std::string> v;
    std::stringstream ss(s);
    for (std::string x; std::getline(ss, x, ',');) v.push_back(x);
    return v;
  };
  for (auto& d : split(dists))
    for (auto& s : split(sizes)) {
      const long long n = (long long)std::stod(s);
      double ms = 0;
      std::size_t out = 0;
      auto t0 = std::chrono::steady_clock::now();
      if (problem == "delaunay2d") {
        auto p = gpugeom::generate2d(d, n, seed);
        std::vector<K::Point_2> q;
        q.reserve(p.size());
        for (auto& x : p) q.emplace_back(x.x, x.y);
        t0 = std::chrono::steady_clock::now();
        CGAL::Delaunay_triangulation_2<K> dt(q.begin(), q.end());
        out = dt.number_of_faces();
      } else if (problem == "delaunay3d") {
        auto p = gpugeom::generate3d(d, n, seed);
        std::vector<K::Point_3> q;
        for (auto& x : p) q.emplace_back(x.x, x.y, x.z);
        t0 = std::chrono::steady_clock::now();
        CGAL::Delaunay_triangulation_3<K> dt(q.begin(), q.end());
        out = dt.number_of_finite_cells();
      } else if (problem == "hull3d") {
        auto p = gpugeom::generate3d(d, n, seed);
        std::vector<K::Point_3> q;
        for (auto& x : p) q.emplace_back(x.x, x.y, x.z);
        t0 = std::chrono::steady_clock::now();
        CGAL::Surface_mesh<K::Point_3> sm;
        CGAL::convex_hull_3(q.begin(), q.end(), sm);
        out = sm.number_of_faces();
      } else if (problem.size() > 2 &&
                 (problem.rfind("insert", 0) == 0 || problem.rfind("move", 0) == 0 ||
                  problem.rfind("remove", 0) == 0)) {
        const std::string what = problem.substr(0, problem.size() - 2);
        if (problem.back() == 'd' && problem[problem.size() - 2] == '2')
          ms = update<DT2, 2>(what, gpugeom::generate2d(d, n, seed), k, move, out);
        else
          ms = update<DT3, 3>(what, gpugeom::generate3d(d, n, seed), k, move, out);
        std::printf("%-11s %-12s %10lld cgal  %10.1f ms  (k %lld, move %g; %zu simplices)\n",
                    problem.c_str(), d.c_str(), n, ms, k, move, out);
        continue;
      } else {
        return std::cerr << "unknown problem " << problem << "\n", 2;
      }
      ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      std::printf("%-11s %-12s %10lld cgal  %10.1f ms  (%zu simplices)\n", problem.c_str(),
                  d.c_str(), n, ms, out);
      if (f)
        f << problem << "," << d << (problem == "delaunay2d" ? "2d" : "3d") << "," << n
          << ",cgal,cpu-1core,0," << ms << ",0," << ms << "," << ms << ",0\n";
    }
  return 0;
}
