// gpugeom delaunay3d: the exact Delaunay tetrahedralisation of a 3D point file, written as a
// tetrahedral mesh (ParaView, TetGen's .node/.ele, NumPy), with an optional exact check.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "cli.hpp"
#include "gpugeom/delaunay3d.hpp"
#include "gpugeom/io.hpp"
#include "verify.hpp"

namespace gpugeom::cli {

namespace {
const char* kHelp =
    "usage: gpugeom delaunay3d POINTS -o MESH [--check] [--compress] [--ascii]\n"
    "                          [--method incremental|digital] [--grid SIDE]\n\n"
    "Exact Delaunay tetrahedralisation of the 3D points in POINTS (.xyz .txt .csv .ply .off\n"
    ".obj .node .npy). Degenerate input (cospherical, coplanar on the hull, duplicates) is\n"
    "resolved by simulation of simplicity; of several copies of a point one is used.\n"
    "  -o MESH     .vtu (ParaView), .vtk (legacy VTK), .ele (with its .node, as TetGen writes\n"
    "              them), .msh (Gmsh), .ply: the input points and the tetrahedra; .npy: the int32\n"
    "              tetrahedron array (T x 4)\n"
    "              indexing the input points, like SciPy's Delaunay.simplices\n"
    "  --compress  .vtu: zlib-compressed blocks\n"
    "  --ascii     .vtu, .vtk and .ply as text instead of binary\n"
    "  --check     verify the result with the independent exact checker\n"
    "  --method M  incremental (default): batches of insertions with parallel flips, then\n"
    "              star splaying where flipping got stuck; digital: the thesis' DigiDel3D (a\n"
    "              digital Voronoi diagram on a grid gives each point a working set of\n"
    "              neighbours, each point's star is built from it and the stars are splayed\n"
    "              until they agree). The same tetrahedra; --verbose shows each method's\n"
    "              phases and counters\n"
    "  --grid SIDE digital: the grid's side along the longest extent (16..1024; default from\n"
    "              the point count, about 32 cells a point, doubled once where more than a\n"
    "              tenth of the points share a cell)\n"
    "With --verbose, the phase table and counters (flips, failed vertices, ...) on stderr.\n"
    "Runs longer than a second show their progress on stderr (not with --quiet).\n";

// A progress line on stderr, redrawn in place, once the run has taken a second (short runs
// print nothing). Returns whether it printed, so the caller can end the line.
void attach_progress(const Global& g, Delaunay3dOptions& o, bool& printed) {
  if (g.quiet) return;
  const auto start = std::chrono::steady_clock::now();
  o.progress = [start, &printed](const Delaunay3dProgress& p) {
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (s < 1.0) return;
    const int width = 30;
    const int done = p.total > 0 ? int(double(width) * double(p.inserted) / double(p.total)) : 0;
    char bar[64];
    for (int i = 0; i < width; ++i) bar[i] = i < done ? '#' : '.';
    bar[width] = 0;
    std::fprintf(stderr, "\r[%s] %-11s %lld / %lld points, batch %lld, %.1f s   ", bar, p.phase,
                 (long long)p.inserted, (long long)p.total, (long long)p.batch, s);
    std::fflush(stderr);
    printed = true;
  };
}
}  // namespace

int cmd_delaunay3d(const Global& g, Args& a) {
  if (a.help()) {
    std::cout << kHelp;
    return kOk;
  }
  Delaunay3dOptions opt;
  opt.backend = g.backend;
  read_method(a, opt);
  PointsToMesh job =
      points_to_mesh(g, a, "delaunay3d", {".vtu", ".vtk", ".msh", ".ele", ".ply", ".npy"},
                     "for tetrahedra", " (see delaunay2d)");
  io::PointSet& p = job.p;
  const std::string& out = job.out;
  const std::string& ext = job.ext;
  const bool check = job.check;
  const std::int64_t n = std::int64_t(p.size());
  bool printed = false;
  attach_progress(g, opt, printed);
  Triangulation3d t3;
  {
    Timer t(g, "delaunay3d");
    try {
      t3 = delaunay3d(p.coords.data(), n, opt);
    } catch (...) {
      if (printed) std::fputs("\n", stderr);  // (the error's message on a line of its own)
      throw;
    }
    if (printed) std::fputs("\n", stderr);  // (before the timer's line)
  }
  if (!g.quiet) {
    std::cout << n << " points";
    if (t3.num_duplicates) std::cout << " (" << t3.num_duplicates << " duplicates kept once)";
    std::cout << " -> " << t3.num_tetrahedra << " tetrahedra, " << t3.hull_facets.size() / 3
              << " hull facets on " << backend_name(t3.stats.backend)
              << (opt.method == Method::Digital ? " (digital method)" : "") << "\n";
    if (g.verbose) print_stats(t3.stats);
  }
  int status = kOk;
  if (check) {
    Timer t(g, "check");
    const auto r = verify::check_delaunay3d(p.coords.data(), n, t3.tetrahedra.data(),
                                            t3.num_tetrahedra, t3.duplicate_of.data());
    if (!r.ok) {
      std::cerr << "INVALID delaunay3d: " << r.message << "\n";
      status = kCheckFailed;
    } else if (!g.quiet) {
      std::cout << "check: valid Delaunay tetrahedralisation\n";
    }
  }
  if (!out.empty()) {
    Timer t(g, "write");
    io::Mesh m;
    m.dim = 3;
    m.cell_size = 4;
    if (ext != ".npy") m.coords = std::move(p.coords);  // (copies are unused vertices)
    m.cells.assign(t3.tetrahedra.begin(), t3.tetrahedra.end());
    if (ext == ".vtu" || ext == ".vtk")  // the duplicate map along, as a point array
      m.point_data.push_back(io::make_data_array("duplicate_of", io::ScalarType::I32, 1,
                                                 t3.duplicate_of.data(), t3.duplicate_of.size()));
    io::write_mesh(out, m, job.wo);
  }
  return status;
}

}  // namespace gpugeom::cli
