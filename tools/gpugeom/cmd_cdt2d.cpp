// gpugeom cdt2d: the exact constrained Delaunay triangulation of Triangle's .poly file (points,
// segments, holes, regional attributes), or of a point file and a segment file.
#include <iostream>

#include "cli.hpp"
#include "draw2d.hpp"
#include "gpugeom/cdt2d.hpp"
#include "gpugeom/io.hpp"
#include "verify.hpp"

namespace gpugeom::cli {

namespace {

const char* kHelp =
    "usage: gpugeom cdt2d IN.poly -o MESH [--hull] [--split] [--check] [--draw F]\n"
    "                     [--poly OUT.poly] [--compress] [--ascii]\n"
    "       gpugeom cdt2d POINTS --segments S.npy -o MESH [--enclosed] [--check]\n\n"
    "Exact constrained Delaunay triangulation: every segment a chain of edges, every other edge\n"
    "locally Delaunay. IN.poly is Triangle's format (points, or a .node beside it; segments;\n"
    "holes; regional attributes); POINTS any 2D point file with --segments an int (m, 2) .npy\n"
    "of point indices (from 0). Segments through points become chains; two segments crossing\n"
    "inside both are refused, naming them, unless --split.\n"
    "  -o MESH        .ele(+.node) .vtu .vtk .msh .ply .off .obj, or .npy (the int32 triangles);\n"
    "                 .vtu/.vtk carry the regions' attribute per triangle\n"
    "  --hull         keep the convex hull's triangles (a .poly's outside is removed by default,\n"
    "                 as Triangle -p does; -c there)\n"
    "  --enclosed     remove the outside of the segments for a point file too\n"
    "  --split        add a vertex where two segments cross (their intersection rounded to\n"
    "                 doubles; the new points follow the input's in the outputs)\n"
    "  --draw F       draw it as SVG or PNG, the segments' edges in blue\n"
    "  --poly F       the result's segment edges as a .poly file (marker: input segment + 1),\n"
    "                 with the points, holes and regions\n"
    "  --check        verify the constrained Delaunay triangulation of the hull the output is cut\n"
    "                 from, with the independent exact checker\n";

}  // namespace

int cmd_cdt2d(const Global& g, Args& a) {
  if (a.help()) {
    std::cout << kHelp;
    return kOk;
  }
  std::string out, seg_path, draw, poly_out;
  a.value("-o", out) || a.value("--output", out);
  a.value("--draw", draw);
  a.value("--poly", poly_out);
  a.value("--segments", seg_path);
  const bool hull = a.flag("--hull"), enclosed = a.flag("--enclosed"), check = a.flag("--check"),
             split = a.flag("--split");
  const io::WriteOptions wo = mesh_write_options(a, out);
  auto pos = a.positionals();
  if (pos.size() != 1) throw UsageError("expected one .poly or point file (see --help)");
  if (out.empty() && !check && draw.empty() && poly_out.empty())
    throw UsageError("nothing to do: give -o MESH, --draw F, --poly F or --check");
  if (hull && enclosed) throw UsageError("--hull and --enclosed exclude each other");
  io::Pslg in;
  const bool poly = pos[0].size() > 5 && pos[0].substr(pos[0].size() - 5) == ".poly";
  {
    Timer t(g, "read");
    if (poly) {
      if (!seg_path.empty()) throw UsageError("a .poly file holds its segments: no --segments");
      in = io::read_poly(pos[0]);
    } else {
      if (seg_path.empty()) throw UsageError("a point file needs --segments S.npy (or give .poly)");
      in.points = io::read_points(pos[0]);
      if (in.points.dim != 2)
        throw Error(ErrorCode::InvalidInput, pos[0] + " holds 3D points: cdt2d needs 2D points");
      in.segments = io::read_segments(seg_path);
    }
  }
  const std::int64_t n = std::int64_t(in.points.size()), m = std::int64_t(in.segments.size() / 2);
  Cdt2dOptions opt;
  opt.backend = g.backend;
  opt.domain = (poly && !hull) || enclosed ? Cdt2dOptions::Domain::Enclosed
                                           : Cdt2dOptions::Domain::ConvexHull;
  if (split) opt.crossings = Cdt2dOptions::Crossings::Split;
  for (std::size_t i = 0; i + 1 < in.holes.size(); i += 2)
    opt.holes.push_back({in.holes[i], in.holes[i + 1]});
  for (std::size_t i = 0; i + 2 < in.regions.size(); i += 3)
    opt.regions.push_back({in.regions[i], in.regions[i + 1], in.regions[i + 2]});
  ConstrainedTriangulation2d r;
  {
    Timer t(g, "triangulate");
    r = cdt2d(in.points.coords.data(), n, in.segments.data(), m, opt);
  }
  if (!g.quiet) {
    std::cout << n << " points, " << m << " segments";
    if (r.zero_length_segments + r.repeated_segments)
      std::cout << " (" << r.zero_length_segments << " zero-length, " << r.repeated_segments
                << " repeated: dropped)";
    if (!r.new_points.empty()) std::cout << ", " << r.new_points.size() / 2 << " crossings split";
    std::cout << " -> " << r.num_triangles << " triangles";
    if (r.removed_triangles) std::cout << " (" << r.removed_triangles << " removed)";
    std::cout << " on " << backend_name(r.stats.backend) << "\n";
    if (g.verbose) print_stats(r.stats);
  }
  int status = kOk;
  if (check) {
    Timer t(g, "check");
    Cdt2dOptions whole = opt;  // the triangulation of the hull the output is cut from
    whole.domain = Cdt2dOptions::Domain::ConvexHull;
    whole.holes.clear();
    whole.regions.clear();
    const auto w = cdt2d(in.points.coords.data(), n, in.segments.data(), m, whole);
    std::vector<std::int32_t> segs;
    std::vector<double> xy(in.points.coords.begin(), in.points.coords.end());
    if (w.new_points.empty()) {
      for (std::size_t s = 0; s < in.segments.size(); s += 2) {
        std::int32_t u = in.segments[s], v = in.segments[s + 1];
        if (w.duplicate_of[u] >= 0) u = w.duplicate_of[u];
        if (w.duplicate_of[v] >= 0) v = w.duplicate_of[v];
        if (u != v) segs.insert(segs.end(), {u, v});
      }
    } else {  // split: the pieces are the segments' marked edges, among all the points
      xy.insert(xy.end(), w.new_points.begin(), w.new_points.end());
      for (std::size_t i = 0; i < w.segment_of.size(); ++i)
        if (w.segment_of[i] >= 0)
          segs.insert(segs.end(), {w.triangles[i - i % 3 + (i % 3 + 1) % 3],
                                   w.triangles[i - i % 3 + (i % 3 + 2) % 3]});
    }
    const auto rep = verify::check_constrained_delaunay2d(
        xy.data(), std::int64_t(xy.size() / 2), w.triangles.data(), w.num_triangles, segs.data(),
        std::int64_t(segs.size() / 2), w.duplicate_of.data());
    if (!rep.ok) {
      std::cerr << "INVALID cdt2d: " << rep.message << "\n";
      status = kCheckFailed;
    } else if (!g.quiet) {
      std::cout << "check: valid constrained Delaunay triangulation\n";
    }
  }
  // The new points follow the input's in every output.
  in.points.coords.insert(in.points.coords.end(), r.new_points.begin(), r.new_points.end());
  if (!draw.empty()) {
    Timer t(g, "draw");
    Triangulation2d tri;  // the drawing's view of the result
    tri.triangles.assign(r.triangles.begin(), r.triangles.end());
    tri.neighbors.assign(r.neighbors.begin(), r.neighbors.end());
    tri.num_triangles = r.num_triangles;
    draw_triangulation(draw, in.points.coords, tri, nullptr, r.segment_of.data());
  }
  if (!poly_out.empty()) {
    Timer t(g, "write");
    io::Pslg edges;  // each segment edge once, marked with its input segment + 1
    edges.points = in.points;
    edges.holes = in.holes;
    edges.regions = in.regions;
    std::vector<std::int32_t> marks;
    for (std::size_t i = 0; i < r.segment_of.size(); ++i) {
      const std::int32_t o = r.neighbors[i];
      if (r.segment_of[i] < 0 || (o >= 0 && std::size_t(o) < i / 3)) continue;
      edges.segments.push_back(r.triangles[i - i % 3 + (i % 3 + 1) % 3]);
      edges.segments.push_back(r.triangles[i - i % 3 + (i % 3 + 2) % 3]);
      marks.push_back(r.segment_of[i] + 1);
    }
    io::write_poly(poly_out, edges, marks.data());
  }
  if (!out.empty()) {
    Timer t(g, "write");
    io::Mesh mesh =
        triangle_mesh2d(std::move(in.points.coords), std::move(r.triangles), r.attribute);
    mesh.point_data.push_back(io::make_data_array("duplicate_of", io::ScalarType::I32, 1,
                                                  r.duplicate_of.data(), r.duplicate_of.size()));
    io::write_mesh(out, mesh, wo);
  }
  return status;
}

}  // namespace gpugeom::cli
