// gpugeom check: judge a triangulation, Delaunay triangulation or convex hull exactly.
#include <iostream>

#include "cli.hpp"
#include "gpugeom/io.hpp"
#include "verify.hpp"

namespace gpugeom::cli {

int cmd_check(const Global& g, Args& a) {
  if (a.help()) {
    std::cout
        << "usage: gpugeom check MESH [--points FILE] [--kind KIND]\n\n"
           "Checks MESH exactly with the independent checkers. The vertices are MESH's own,\n"
           "or FILE's points when given (for cells-only files such as .npy). KIND is one of\n"
           "  delaunay2d  triangulation2d  delaunay3d  triangulation3d  hull3d\n"
           "and defaults to delaunay2d for 2D triangles, delaunay3d for tetrahedra and hull3d\n"
           "for 3D triangles. Exit status 0 when valid, 1 when not.\n";
    return kOk;
  }
  std::string points, kind;
  a.value("--points", points);
  a.value("--kind", kind);
  auto pos = a.positionals();
  if (pos.size() != 1) throw UsageError("expected one mesh file");
  io::Mesh m;
  io::PointSet p;
  {
    Timer t(g, "read");
    m = io::read_mesh(pos[0]);
    if (!points.empty()) {
      p = io::read_points(points);
    } else {
      if (m.coords.empty())
        throw UsageError(pos[0] + " holds no vertices: give them with --points FILE");
      p.dim = m.dim;
      p.coords = m.coords;
    }
  }
  if (kind.empty()) kind = m.cell_size == 4 ? "delaunay3d" : (p.dim == 2 ? "delaunay2d" : "hull3d");
  const int need_dim = kind.back() == 'd' ? kind[kind.size() - 2] - '0' : 0;
  if ((kind == "delaunay2d" || kind == "triangulation2d" || kind == "delaunay3d" ||
       kind == "triangulation3d" || kind == "hull3d") == false)
    throw UsageError("unknown --kind '" + kind + "'");
  if (need_dim && p.dim != need_dim)
    throw Error(ErrorCode::InvalidInput, "a " + kind + " check needs " + std::to_string(need_dim) +
                                             "D points, these are " + std::to_string(p.dim) + "D");
  const int want_cell = (kind == "delaunay3d" || kind == "triangulation3d") ? 4 : 3;
  if (m.cell_size != want_cell)
    throw Error(ErrorCode::InvalidInput,
                "a " + kind + " check needs cells of " + std::to_string(want_cell) +
                    " vertices, the mesh has " + std::to_string(m.cell_size));
  const std::int64_t n = std::int64_t(p.size()), nc = std::int64_t(m.num_cells());
  verify::Report r;
  {
    Timer t(g, "check");
    if (kind == "delaunay2d")
      r = verify::check_delaunay2d(p.coords.data(), n, m.cells.data(), nc);
    else if (kind == "triangulation2d")
      r = verify::check_triangulation2d(p.coords.data(), n, m.cells.data(), nc);
    else if (kind == "delaunay3d")
      r = verify::check_delaunay3d(p.coords.data(), n, m.cells.data(), nc);
    else if (kind == "triangulation3d")
      r = verify::check_triangulation3d(p.coords.data(), n, m.cells.data(), nc);
    else
      r = verify::check_hull3d(p.coords.data(), n, m.cells.data(), nc);
  }
  if (!r.ok) {
    std::cerr << "INVALID " << kind << ": " << r.message << "\n";
    return kCheckFailed;
  }
  if (!g.quiet) {
    std::cout << "valid " << kind << "\n";
    for (auto& s : r.notes) std::cout << "  " << s << "\n";
  }
  return kOk;
}

}  // namespace gpugeom::cli
