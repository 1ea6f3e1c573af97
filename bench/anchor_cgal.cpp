// CGAL anchors, timed on the same generated points as gpugeom's benchmarks (one CPU core, exact
// predicates kernel): 2D/3D Delaunay triangulation and the 3D convex hull.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "gpugeom/generate.hpp"

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

int main(int argc, char** argv) {
  std::string problem = "delaunay2d", dists = "uniform", sizes = "100000", csv;
  unsigned long long seed = 1;
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
