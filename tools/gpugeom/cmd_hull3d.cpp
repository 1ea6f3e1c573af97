// gpugeom hull3d: the exact convex hull of a 3D point file, written as a mesh, with an
// optional exact check of the result.
#include <cstdio>
#include <iostream>

#include "cli.hpp"
#include "gpugeom/hull3d.hpp"
#include "gpugeom/io.hpp"
#include "verify.hpp"

namespace gpugeom::cli {

namespace {
const char* kHelp =
    "usage: gpugeom hull3d POINTS -o MESH [--check] [--compress] [--ascii]\n"
    "                      [--method incremental|digital] [--grid SIDE]\n\n"
    "Exact convex hull of the 3D points in POINTS (.xyz .txt .csv .ply .off .obj .node .npy).\n"
    "Only extreme points become vertices: points inside a face or on an edge do not, and of\n"
    "several copies of a point one does.\n"
    "  -o MESH     .ply .off .obj .vtu: the hull as a mesh of its vertices, facets\n"
    "              counter-clockwise seen from outside; .npy: the int32 facet array (F x 3)\n"
    "              indexing the input points, like SciPy's ConvexHull.simplices\n"
    "  --compress  .vtu: zlib-compressed blocks\n"
    "  --ascii     .vtu and .ply as text instead of binary\n"
    "  --check     verify the result with the independent exact checker\n"
    "  --method M  incremental (default): star-shaped construction and Flip-Flop; digital:\n"
    "              the thesis' DigiHull3D (a slice of the digital Voronoi diagram on each face\n"
    "              of a grid gives a first hull, a digital depth test keeps the points that may\n"
    "              lie outside it, the hull of those is the hull). The same result; --verbose\n"
    "              shows each method's phases and counters\n"
    "  --grid SIDE digital: the faces' grid side (16..8192; default from the point count, at\n"
    "              most 1024)\n";
}  // namespace

int cmd_hull3d(const Global& g, Args& a) {
  if (a.help()) {
    std::cout << kHelp;
    return kOk;
  }
  Hull3dOptions opt;
  opt.backend = g.backend;
  read_method(a, opt);
  PointsToMesh job = points_to_mesh(g, a, "hull3d",
                                    {".ply", ".off", ".obj", ".vtu", ".vtk", ".npy"}, "for a hull");
  const io::PointSet& p = job.p;
  const std::string& out = job.out;
  const std::string& ext = job.ext;
  const bool check = job.check;
  const std::int64_t n = std::int64_t(p.size());
  ConvexHull3d h;
  {
    Timer t(g, "hull");
    h = convex_hull3d(p.coords.data(), n, opt);
  }
  if (!g.quiet) {
    std::cout << n << " points -> " << h.vertices.size() << " extreme points, " << h.num_facets
              << " facets on " << backend_name(h.stats.backend)
              << (opt.method == Method::Digital ? " (digital method)" : "") << "\n";
    if (g.verbose) print_stats(h.stats);
  }
  int status = kOk;
  if (check) {
    Timer t(g, "check");
    const auto r = verify::check_hull3d(p.coords.data(), n, h.triangles.data(), h.num_facets);
    if (!r.ok) {
      std::cerr << "INVALID hull3d: " << r.message << "\n";
      status = kCheckFailed;
    } else if (!g.quiet) {
      std::cout << "check: valid convex hull";
      for (auto& note : r.notes)
        if (note.find("only") != std::string::npos) std::cout << " (" << note << ")";
      std::cout << "\n";
    }
  }
  if (!out.empty()) {
    Timer t(g, "write");
    io::Mesh m;
    m.dim = 3;
    m.cell_size = 3;
    if (ext == ".npy") {
      m.cells.assign(h.triangles.begin(), h.triangles.end());
    } else {  // a compact mesh of the hull's vertices
      std::vector<std::int32_t> index(std::size_t(n), -1);
      for (std::size_t i = 0; i < h.vertices.size(); ++i) {
        index[h.vertices[i]] = std::int32_t(i);
        for (int d = 0; d < 3; ++d)
          m.coords.push_back(p.coords[3 * std::size_t(h.vertices[i]) + d]);
      }
      m.cells.reserve(h.triangles.size());
      for (auto v : h.triangles) m.cells.push_back(index[v]);
    }
    io::write_mesh(out, m, job.wo);
  }
  return status;
}

}  // namespace gpugeom::cli
