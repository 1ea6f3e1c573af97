// gpugeom mesh2d: a quality mesh of Triangle's .poly domain (Delaunay refinement: Triangle's -q
// and -a), with the quality histogram printed, the mesh checked on request.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "cli.hpp"
#include "draw2d.hpp"
#include "gpugeom/io.hpp"
#include "gpugeom/refine2d.hpp"
#include "verify.hpp"

namespace gpugeom::cli {

namespace {

const char* kHelp =
    "usage: gpugeom mesh2d IN.poly -o MESH [-q ANGLE] [-a AREA] [-S N] [--hull] [--split]\n"
    "                      [--check] [--draw F] [--compress] [--ascii]\n\n"
    "A quality triangular mesh of the domain a .poly file describes (Triangle's format: points,\n"
    "segments, holes, regional attributes and areas): every angle at least ANGLE and every\n"
    "triangle at most its area bound, except where the input forces smaller angles (counted).\n"
    "The mesh is exact: constrained Delaunay, every segment covered.\n"
    "  -q ANGLE   the smallest angle, degrees (default 20; at most 33.8, as Triangle)\n"
    "  -a AREA    the largest triangle area (the .poly's regional areas apply as well)\n"
    "  -S N       at most N Steiner points\n"
    "  -o MESH    .ele(+.node) .vtu .vtk .msh (Gmsh) .ply .off .obj, or .npy (the int32\n"
    "             triangles); .vtu/.vtk carry the regions' attribute per triangle, .msh their\n"
    "             integer attributes as physical tags\n"
    "  --hull     mesh the convex hull (its edges become segments; Triangle -c)\n"
    "  --split    add a vertex where two segments cross\n"
    "  --draw F   draw it as SVG or PNG, the segments' edges in blue\n"
    "  --check    verify the mesh with the independent exact checker: constrained Delaunay,\n"
    "             segments covered, the bounds met\n";

// The smallest angle (degrees) and the area of triangle t.
void measure(const double* xy, const std::int32_t* tri, std::size_t t, double& angle,
             double& area) {
  const double* p[3];
  for (int k = 0; k < 3; ++k) p[k] = xy + 2 * std::size_t(tri[3 * t + k]);
  area =
      0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
  angle = 180;
  for (int k = 0; k < 3; ++k) {
    const double ux = p[(k + 1) % 3][0] - p[k][0], uy = p[(k + 1) % 3][1] - p[k][1];
    const double vx = p[(k + 2) % 3][0] - p[k][0], vy = p[(k + 2) % 3][1] - p[k][1];
    angle = std::min(angle, std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 /
                                3.14159265358979323846);
  }
}

// The quality histogram: smallest angles in 10-degree bins, and the areas' spread.
void print_quality(const RefinedMesh2d& r) {
  std::size_t bins[6] = {0, 0, 0, 0, 0, 0};
  std::vector<double> areas(r.num_triangles);
  double worst = 180;
  for (std::size_t t = 0; t < r.num_triangles; ++t) {
    double a, s;
    measure(r.points.data(), r.triangles.data(), t, a, s);
    bins[std::min<std::size_t>(5, std::size_t(a / 10))]++;
    areas[t] = s;
    worst = std::min(worst, a);
  }
  std::printf("smallest angles:");
  for (int b = 0; b < 6; ++b) std::printf("  %d-%d: %zu", 10 * b, 10 * b + 10, bins[b]);
  std::printf("  (worst %.2f degrees)\n", worst);
  if (!areas.empty()) {
    std::sort(areas.begin(), areas.end());
    std::printf("areas: min %.3g, median %.3g, max %.3g\n", areas.front(), areas[areas.size() / 2],
                areas.back());
  }
}

}  // namespace

int cmd_mesh2d(const Global& g, Args& a) {
  if (a.help()) {
    std::cout << kHelp;
    return kOk;
  }
  std::string out, draw, q, area, steiner;
  a.value("-o", out) || a.value("--output", out);
  a.value("--draw", draw);
  a.value("-q", q);
  a.value("-a", area);
  a.value("-S", steiner);
  const bool hull = a.flag("--hull"), check = a.flag("--check"), split = a.flag("--split");
  const io::WriteOptions wo = mesh_write_options(a, out);
  auto pos = a.positionals();
  if (pos.size() != 1) throw UsageError("expected one .poly file (see --help)");
  if (out.empty() && !check && draw.empty())
    throw UsageError("nothing to do: give -o MESH, --draw F or --check");
  Refine2dOptions opt;
  opt.backend = g.backend;
  opt.domain = hull ? Cdt2dOptions::Domain::ConvexHull : Cdt2dOptions::Domain::Enclosed;
  if (split) opt.crossings = Cdt2dOptions::Crossings::Split;
  opt.min_angle = q.empty() ? 20.0 : to_real(q, "-q");
  opt.max_area = area.empty() ? 0.0 : to_real(area, "-a");
  if (!steiner.empty()) opt.max_steiner_points = std::int64_t(to_real(steiner, "-S"));
  io::Pslg in;
  {
    Timer t(g, "read");
    in = io::read_poly(pos[0]);
  }
  for (std::size_t i = 0; i + 1 < in.holes.size(); i += 2)
    opt.holes.push_back({in.holes[i], in.holes[i + 1]});
  for (std::size_t i = 0; i + 2 < in.regions.size(); i += 3)
    opt.regions.push_back({in.regions[i], in.regions[i + 1], in.regions[i + 2],
                           i / 3 < in.region_areas.size() ? in.region_areas[i / 3] : 0.0});
  const std::int64_t n = std::int64_t(in.points.size()), m = std::int64_t(in.segments.size() / 2);
  RefinedMesh2d r;
  {
    Timer t(g, "mesh");
    r = refine2d(in.points.coords.data(), n, in.segments.data(), m, opt);
  }
  if (!g.quiet) {
    std::cout << n << " points, " << m << " segments -> " << r.num_points << " vertices, "
              << r.num_triangles << " triangles (" << r.stats.rounds << " rounds) on "
              << backend_name(r.stats.backend) << "\n";
    print_quality(r);
    if (!r.small_angles.empty()) {
      std::size_t why[4] = {0, 0, 0, 0};
      for (auto w : r.small_angle_reasons) why[std::size_t(w) & 3]++;
      std::cout << r.small_angles.size() << " triangles keep an angle below " << opt.min_angle
                << " degrees: " << why[1] << " at input angles, " << why[2]
                << " in the shells of small input angles, " << why[3] << " at the limit\n";
    }
    if (!r.large_triangles.empty())
      std::cout << r.large_triangles.size() << " triangles stay above their area bound (-S)\n";
    if (g.verbose) print_stats(r.stats);
  }
  int status = kOk;
  if (check) {
    Timer t(g, "check");
    const auto rep = verify::check_refined_mesh2d(
        r.points.data(), r.num_points, r.triangles.data(), r.num_triangles, r.segment_of.data(),
        in.segments.data(), m, r.duplicate_of.data(), opt.min_angle, opt.max_area,
        r.small_angles.data(), std::int64_t(r.small_angles.size()));
    if (!rep.ok) {
      std::cerr << "INVALID mesh2d: " << rep.message << "\n";
      status = kCheckFailed;
    } else if (!g.quiet) {
      std::cout << "check: valid quality mesh (constrained Delaunay, segments covered, bounds "
                   "met)\n";
    }
  }
  HostVector<double> coords = std::move(r.points);
  if (!draw.empty()) {
    Timer t(g, "draw");
    Triangulation2d tri;
    tri.triangles.assign(r.triangles.begin(), r.triangles.end());
    tri.neighbors.assign(r.neighbors.begin(), r.neighbors.end());
    tri.num_triangles = r.num_triangles;
    draw_triangulation(draw, coords, tri, nullptr, r.segment_of.data());
  }
  if (!out.empty()) {
    Timer t(g, "write");
    io::write_mesh(out, triangle_mesh2d(std::move(coords), std::move(r.triangles), r.attribute),
                   wo);
  }
  return status;
}

}  // namespace gpugeom::cli
