// gpugeom delaunay2d: the exact Delaunay triangulation of a 2D point file, its Voronoi diagram,
// a drawing a person can look at, and an optional exact check of the result.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "cli.hpp"
#include "draw2d.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/io.hpp"
#include "verify.hpp"

namespace gpugeom::cli {

namespace {

const char* kHelp =
    "usage: gpugeom delaunay2d POINTS -o MESH [--voronoi VOR.json] [--clip xmin,ymin,xmax,ymax]\n"
    "                          [--draw FILE.svg|FILE.png] [--check] [--compress] [--ascii]\n"
    "                          [--method incremental|digital] [--grid SIDE]\n\n"
    "Exact Delaunay triangulation of the 2D points in POINTS (.xyz .txt .csv .ply .off .obj\n"
    ".node .npy; 3D files are accepted when every z is 0). Duplicate points are kept once.\n"
    "  -o MESH        .ply .off .obj .ele(+.node) .vtu .vtk .msh, or .npy (the int32 triangles)\n"
    "  --compress     .vtu: zlib-compressed blocks (ParaView reads them)\n"
    "  --ascii        .vtu, .vtk and .ply as text instead of binary\n"
    "  --voronoi F    the Voronoi diagram as JSON in SciPy's terms: vertices, ridge_points,\n"
    "                 ridge_vertices, regions (one per input point, -1 first when unbounded)\n"
    "  --clip BOX     also the cells clipped to BOX, as polygons (\"clipped\" in the JSON);\n"
    "                 the default box is the points' bounding box grown by 10 %\n"
    "  --draw F       draw the triangulation (and the Voronoi diagram with --voronoi) as SVG\n"
    "                 or PNG (also --svg F)\n"
    "  --check        verify the result with the independent exact checker\n"
    "  --method M     incremental (default): batches of insertions and parallel flips; digital:\n"
    "                 the thesis' digital method (a digital Voronoi diagram on a grid, its dual\n"
    "                 shifted to the points, the rest inserted and flipped). The same result;\n"
    "                 --verbose shows each method's phases and counters\n"
    "  --grid SIDE    digital: the grid's longer side in pixels (4..46338; default: about 4\n"
    "                 pixels a point, at most 16384)\n";

template <class V>
std::string json_array(const V& v, int per) {
  std::string s = "[";
  char buf[64];
  for (std::size_t i = 0; i < v.size(); i += per) {
    s += i ? ",[" : "[";
    for (int k = 0; k < per; ++k) {
      std::snprintf(buf, sizeof buf, "%s%.17g", k ? "," : "", v[i + k]);
      s += buf;
    }
    s += "]";
  }
  return s + "]";
}
template <class T>
std::string json_pairs(const HostVector<T>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); i += 2)
    s += (i ? ",[" : "[") + std::to_string(v[i]) + "," + std::to_string(v[i + 1]) + "]";
  return s + "]";
}

std::string voronoi_json(const Voronoi2d& v, const ClippedCells* clip) {
  std::string s = "{\n\"vertices\": " + json_array(v.vertices, 2);
  s += ",\n\"ridge_points\": " + json_pairs(v.ridge_points);
  s += ",\n\"ridge_vertices\": " + json_pairs(v.ridge_vertices);
  s += ",\n\"ridge_directions\": " + json_array(v.ridge_directions, 2);
  s += ",\n\"regions\": [";
  for (std::size_t i = 0; i + 1 < v.cell_offsets.size(); ++i) {
    s += i ? ",[" : "[";
    for (std::int64_t j = v.cell_offsets[i]; j < v.cell_offsets[i + 1]; ++j)
      s += (j > v.cell_offsets[i] ? "," : "") + std::to_string(v.cell_vertices[j]);
    s += "]";
  }
  s += "]";
  if (clip) {
    s += ",\n\"clipped\": [";
    for (std::size_t i = 0; i + 1 < clip->offsets.size(); ++i) {
      std::vector<double> poly(clip->xy.begin() + 2 * clip->offsets[i],
                               clip->xy.begin() + 2 * clip->offsets[i + 1]);
      s += (i ? "," : "") + json_array(poly, 2);
    }
    s += "]";
  }
  return s + "\n}\n";
}

std::vector<double> parse_box(const std::string& s) {
  const std::vector<double> b = to_reals(s, "--clip");
  if (b.size() != 4 || !(b[0] < b[2] && b[1] < b[3]))
    throw UsageError("--clip takes xmin,ymin,xmax,ymax with xmin < xmax and ymin < ymax");
  return b;
}

}  // namespace

int cmd_delaunay2d(const Global& g, Args& a) {
  if (a.help()) {
    std::cout << kHelp;
    return kOk;
  }
  std::string out, vor_path, draw, clip_s;
  a.value("-o", out) || a.value("--output", out);
  a.value("--voronoi", vor_path);
  a.value("--clip", clip_s);
  a.value("--draw", draw) || a.value("--svg", draw);
  const bool check = a.flag("--check");
  Delaunay2dOptions opt;
  opt.backend = g.backend;
  read_method(a, opt);
  const io::WriteOptions wo = mesh_write_options(a, out);
  auto pos = a.positionals();
  if (pos.size() != 1) throw UsageError("expected one point file (see --help)");
  if (out.empty() && vor_path.empty() && draw.empty() && !check)
    throw UsageError("nothing to do: give -o MESH, --voronoi F, --draw F or --check");
  io::PointSet p;
  {
    Timer t(g, "read");
    p = io::read_points(pos[0]);
  }
  if (p.dim == 3) {  // accept planar files written as 3D
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.coords[3 * i + 2] != 0)
        throw Error(ErrorCode::InvalidInput, pos[0] + " holds 3D points (point " +
                                                 std::to_string(i) +
                                                 " has z != 0): delaunay2d needs 2D points");
    HostVector<double> xy(2 * p.size());
    for (std::size_t i = 0; i < p.size(); ++i)
      xy[2 * i] = p.coords[3 * i], xy[2 * i + 1] = p.coords[3 * i + 1];
    p.coords.swap(xy);
    p.dim = 2;
  }
  const std::int64_t n = std::int64_t(p.size());
  Triangulation2d tri;
  {
    Timer t(g, "triangulate");
    tri = delaunay2d(p.coords.data(), n, opt);
  }
  if (!g.quiet) {
    std::cout << n << " points";
    if (tri.num_duplicates) std::cout << " (" << tri.num_duplicates << " duplicates kept once)";
    std::cout << " -> " << tri.num_triangles << " triangles on " << backend_name(tri.stats.backend)
              << (opt.method == Method::Digital ? " (digital method)" : "") << "\n";
    if (g.verbose) print_stats(tri.stats);
  }
  int status = kOk;
  if (check) {
    Timer t(g, "check");
    const auto r = verify::check_delaunay2d(p.coords.data(), n, tri.triangles.data(),
                                            tri.num_triangles, tri.duplicate_of.data());
    if (!r.ok) {
      std::cerr << "INVALID delaunay2d: " << r.message << "\n";
      status = kCheckFailed;
    } else if (!g.quiet) {
      std::cout << "check: valid Delaunay triangulation\n";
    }
  }
  if (!out.empty()) {
    Timer t(g, "write");
    // The points and triangles lent to the mesh for the write (swapped in and back: no copy).
    io::Mesh m;
    m.dim = 2;
    m.cell_size = 3;
    const bool whole = tri.triangles.size() == 3 * tri.num_triangles;
    m.coords.swap(p.coords);
    if (whole)
      m.cells.swap(tri.triangles);
    else
      m.cells.assign(tri.triangles.begin(), tri.triangles.begin() + 3 * tri.num_triangles);
    struct Back {  // (also when the write throws)
      io::Mesh& m;
      io::PointSet& p;
      Triangulation2d& t;
      bool whole;
      ~Back() {
        m.coords.swap(p.coords);
        if (whole) m.cells.swap(t.triangles);
      }
    } back{m, p, tri, whole};
    // .vtu and .vtk carry the duplicate map along (ParaView shows it as a point array).
    m.point_data.push_back(io::make_data_array("duplicate_of", io::ScalarType::I32, 1,
                                               tri.duplicate_of.data(), tri.duplicate_of.size()));
    io::write_mesh(out, m, wo);
  }
  Voronoi2d vor;
  ClippedCells clipped;
  const bool want_vor = !vor_path.empty();
  if (want_vor) {
    Timer t(g, "voronoi");
    vor = voronoi2d(p.coords.data(), n, tri, options_from<Voronoi2dOptions>(opt));
    std::vector<double> box;
    if (!clip_s.empty()) box = parse_box(clip_s);
    if (!box.empty() || !draw.empty()) {
      if (box.empty()) box = grown_box(p.coords, 0.1);
      clipped = clip_voronoi_cells(p.coords.data(), n, tri, vor, box[0], box[1], box[2], box[3]);
    }
    io::write_text(vor_path, voronoi_json(vor, clip_s.empty() ? nullptr : &clipped));
  } else if (!clip_s.empty()) {
    throw UsageError("--clip needs --voronoi");
  }
  if (!draw.empty()) {
    Timer t(g, "draw");
    draw_triangulation(draw, p.coords, tri, want_vor ? &clipped : nullptr);
  }
  return status;
}

}  // namespace gpugeom::cli
