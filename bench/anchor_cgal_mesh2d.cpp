// CGAL's 2D Delaunay mesher (Mesh_2: refine_Delaunay_mesh_2 over a constrained Delaunay
// triangulation, exact predicates kernel, one core) on a .poly domain, the anchor beside
// gpugeom.mesh2d and Triangle in bench/mesh2d.py.
//
//   anchor_cgal_mesh2d DOMAIN.poly ANGLE AREA [REPEAT]
//
// CGAL bounds the circumradius over the shortest edge (b = sin^2 of the smallest angle) and the
// longest edge, not the area: the edge bound used is the side of the equilateral triangle of
// area AREA, so every triangle meets the area bound as well (a stricter bound than Triangle's
// and gpugeom's; the counts say how much). The .poly's holes are the mesher's seeds (their
// components are left out). Prints "ms triangles" (the best of REPEAT runs; triangles in the
// domain).
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <list>
#include <string>
#include <vector>

#include "gpugeom/io.hpp"

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Delaunay_mesh_vertex_base_2<K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<CDT>;
}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: anchor_cgal_mesh2d DOMAIN.poly ANGLE AREA [REPEAT]\n");
    return 2;
  }
  const gpugeom::io::Pslg g = gpugeom::io::read_poly(argv[1]);
  const double angle = std::atof(argv[2]), area = std::atof(argv[3]);
  const int repeat = argc > 4 ? std::max(1, std::atoi(argv[4])) : 1;
  const double pi = 3.14159265358979323846;
  const double b = std::pow(std::sin(angle * pi / 180), 2);
  const double edge = area > 0 ? std::sqrt(4 * area / std::sqrt(3.0)) : 0.0;
  const std::size_t n = g.points.coords.size() / 2;
  double best = 1e300;
  std::size_t faces = 0;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    CDT cdt;
    std::vector<CDT::Vertex_handle> v(n);
    for (std::size_t i = 0; i < n; ++i)
      v[i] = cdt.insert(K::Point_2(g.points.coords[2 * i], g.points.coords[2 * i + 1]));
    for (std::size_t j = 0; j + 1 < g.segments.size(); j += 2)
      if (v[std::size_t(g.segments[j])] != v[std::size_t(g.segments[j + 1])])
        cdt.insert_constraint(v[std::size_t(g.segments[j])], v[std::size_t(g.segments[j + 1])]);
    std::list<K::Point_2> seeds;
    for (std::size_t h = 0; h + 1 < g.holes.size(); h += 2)
      seeds.emplace_back(g.holes[h], g.holes[h + 1]);
    CGAL::refine_Delaunay_mesh_2(cdt, seeds.begin(), seeds.end(), Criteria(b, edge));
    faces = 0;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
      if (f->is_in_domain()) ++faces;
    best = std::min(
        best,
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::printf("%.3f %zu\n", best, faces);
  return 0;
}
