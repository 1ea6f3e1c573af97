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
    "usage: gpugeom hull3d POINTS -o MESH [--check] [--compress] [--ascii]\n\n"
    "Exact convex hull of the 3D points in POINTS (.xyz .txt .csv .ply .off .obj .node .npy).\n"
    "Only extreme points become vertices: points inside a face or on an edge do not, and of\n"
    "several copies of a point one does.\n"
    "  -o MESH     .ply .off .obj .vtu: the hull as a mesh of its vertices, facets\n"
    "              counter-clockwise seen from outside; .npy: the int32 facet array (F x 3)\n"
    "              indexing the input points, like SciPy's ConvexHull.simplices\n"
    "  --compress  .vtu: zlib-compressed blocks\n"
    "  --ascii     .vtu and .ply as text instead of binary\n"
    "  --check     verify the result with the independent exact checker\n";
}  // namespace

int cmd_hull3d(const Global& g, Args& a) {
  if (a.help()) {
    std::cout << kHelp;
    return kOk;
  }
  std::string out;
  a.value("-o", out) || a.value("--output", out);
  const bool check = a.flag("--check");
  const io::WriteOptions wo = mesh_write_options(a, out);
  auto pos = a.positionals();
  if (pos.size() != 1) throw UsageError("expected one point file (see --help)");
  if (out.empty() && !check) throw UsageError("nothing to do: give -o MESH or --check");
  const std::string ext = out.empty() ? "" : io::extension(out);
  if (!out.empty() && ext != ".ply" && ext != ".off" && ext != ".obj" && ext != ".vtu" &&
      ext != ".npy")
    throw UsageError("-o takes .ply, .off, .obj, .vtu or .npy for a hull (got '" + out + "')");
  io::PointSet p;
  {
    Timer t(g, "read");
    p = io::read_points(pos[0]);
  }
  if (p.dim != 3)
    throw Error(ErrorCode::InvalidInput, pos[0] + " holds 2D points: hull3d needs 3D points");
  const std::int64_t n = std::int64_t(p.size());
  Hull3dOptions opt;
  opt.backend = g.backend;
  ConvexHull3d h;
  {
    Timer t(g, "hull");
    h = convex_hull3d(p.coords.data(), n, opt);
  }
  if (!g.quiet) {
    std::cout << n << " points -> " << h.vertices.size() << " extreme points, " << h.num_facets()
              << " facets on " << backend_name(h.stats.backend) << "\n";
    if (g.verbose) print_stats(h.stats);
  }
  int status = kOk;
  if (check) {
    Timer t(g, "check");
    const auto r =
        verify::check_hull3d(p.coords.data(), n, h.triangles.data(), std::int64_t(h.num_facets()));
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
      m.cells = h.triangles;
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
    io::write_mesh(out, m, wo);
  }
  return status;
}

}  // namespace gpugeom::cli
