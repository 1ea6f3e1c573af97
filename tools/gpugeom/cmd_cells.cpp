// gpugeom cells: the Voronoi cells of a 3D particle file in a box, bounded or periodic (issue
// 49), written as a table of per-cell measures for the analysis tools of particle codes.
#include <cmath>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "gpugeom/io.hpp"
#include "gpugeom/voronoi_cells.hpp"

namespace gpugeom::cli {

namespace {
const char* kHelp =
    "usage: gpugeom cells POINTS --box LO,HI | --box X0,Y0,Z0,X1,Y1,Z1 [--periodic AXES]\n"
    "                     [-o CELLS] [--check]\n\n"
    "The Voronoi cell of every 3D point in POINTS (.xyz .txt .csv .ply .off .obj .node .npy)\n"
    "within a box: cut by its walls, or wrapping round along periodic axes, as Voro++ and freud\n"
    "compute them. The neighbours are exact (the Delaunay tetrahedralisation's ridges).\n"
    "  --box B        the box: LO,HI for a cube or X0,Y0,Z0,X1,Y1,Z1\n"
    "  --periodic A   the axes that wrap round: any of x, y, z, or 'all' (default none); along\n"
    "                 them coordinates are taken modulo the box, along the others points must\n"
    "                 lie in it\n"
    "  -o CELLS       .csv: one row per point (point, volume, area, centroid x y z, neighbours,\n"
    "                 with a header); .npy: float64 (n, 6): volume, area, centroid x y z,\n"
    "                 neighbour count. A copy of an earlier point has an empty cell (volume 0)\n"
    "  --check        the volumes must sum to the box's volume (relative 1e-9) and each cell\n"
    "                 but a copy's must have a positive volume; exit status 1 otherwise\n"
    "With --verbose, the phase table and counters on stderr.\n";

}  // namespace

int cmd_cells(const Global& g, Args& a) {
  if (a.help()) {
    std::cout << kHelp;
    return kOk;
  }
  std::string out, box_s, periodic_s;
  a.value("-o", out);
  a.value("--box", box_s);
  a.value("--periodic", periodic_s);
  const bool check = a.flag("--check");
  const std::vector<std::string> pos = a.positionals();
  if (pos.size() != 1) throw UsageError("give one point file (gpugeom cells --help)");
  if (box_s.empty()) throw UsageError("--box is needed: the cells are cut by (or wrap round) it");
  const std::string ext = out.empty() ? "" : io::extension(out);
  if (!out.empty() && ext != ".csv" && ext != ".npy")
    throw UsageError("-o " + out + ": the cells are written as .csv or .npy");
  VoronoiCellsOptions opt;
  opt.backend = g.backend;
  opt.polygons = false;
  const std::vector<double> b = to_reals(box_s, "--box");
  if (b.size() == 2) {
    for (int d = 0; d < 3; ++d) opt.lo[d] = b[0], opt.hi[d] = b[1];
  } else if (b.size() == 6) {
    for (int d = 0; d < 3; ++d) opt.lo[d] = b[d], opt.hi[d] = b[3 + d];
  } else {
    throw UsageError("--box takes 2 numbers (LO,HI) or 6 (X0,Y0,Z0,X1,Y1,Z1), got " +
                     std::to_string(b.size()));
  }
  if (periodic_s == "all") periodic_s = "xyz";
  for (char c : periodic_s) {
    if (c < 'x' || c > 'z') throw UsageError("--periodic takes the letters x, y, z or 'all'");
    opt.periodic[c - 'x'] = true;
  }
  if (out.empty() && !check) throw UsageError("nothing to do: give -o CELLS or --check");
  io::PointSet p;
  {
    Timer t(g, "read");
    p = io::read_points(pos[0]);
  }
  if (p.dim != 3) throw Error(ErrorCode::InvalidInput, pos[0] + " holds 2D points: cells are 3D");
  const std::int64_t n = std::int64_t(p.size());
  VoronoiCells c;
  {
    Timer t(g, "cells");
    c = voronoi_cells(p.coords.data(), n, opt);
  }
  double total = 0, box_volume = 1;
  for (double v : c.volumes) total += v;
  for (int d = 0; d < 3; ++d) box_volume *= opt.hi[d] - opt.lo[d];
  const std::int64_t faces = std::int64_t(c.neighbors.size());
  if (!g.quiet) {
    std::cout << n << " points -> " << n << " cells, " << faces << " faces ("
              << (n ? double(faces) / double(n) : 0.0) << " a cell), volume " << total
              << " of the box's " << box_volume << " on " << backend_name(c.stats.backend) << "\n";
    if (g.verbose) print_stats(c.stats);
  }
  int status = kOk;
  if (check) {
    std::int64_t empty = 0, copies = 0;
    for (std::int64_t i = 0; i < n; ++i) {
      const bool copy = c.face_offsets[i + 1] == c.face_offsets[i] && c.volumes[i] == 0;
      empty += !(c.volumes[i] > 0) && !copy;
      copies += copy;
    }
    const double err = std::fabs(total - box_volume) / box_volume;
    if (err > 1e-9 || empty) {
      std::cerr << "INVALID cells: the volumes sum to " << total << " (relative error " << err
                << ") for a box of " << box_volume << "; " << empty << " cell(s) without volume\n";
      status = kCheckFailed;
    } else if (!g.quiet) {
      std::cout << "check: the cells fill the box (relative error " << err << ")"
                << (copies ? ", " + std::to_string(copies) + " copies with empty cells" : "")
                << "\n";
    }
  }
  if (!out.empty()) {
    Timer t(g, "write");
    if (ext == ".csv") {
      std::string s = "point,volume,area,centroid_x,centroid_y,centroid_z,neighbors\n";
      char line[256];
      for (std::int64_t i = 0; i < n; ++i) {
        std::snprintf(line, sizeof line, "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%lld\n", (long long)i,
                      c.volumes[i], c.areas[i], c.centroids[3 * i], c.centroids[3 * i + 1],
                      c.centroids[3 * i + 2],
                      (long long)(c.face_offsets[i + 1] - c.face_offsets[i]));
        s += line;
      }
      io::write_text(out, s);
    } else {
      io::Grid grid;
      grid.shape = {n, 6};
      grid.type = io::ScalarType::F64;
      grid.data.resize(std::size_t(n) * 6 * sizeof(double));
      for (std::int64_t i = 0; i < n; ++i) {
        const double row[6] = {
            c.volumes[i],           c.areas[i],
            c.centroids[3 * i],     c.centroids[3 * i + 1],
            c.centroids[3 * i + 2], double(c.face_offsets[i + 1] - c.face_offsets[i])};
        std::memcpy(grid.data.data() + std::size_t(i) * sizeof row, row, sizeof row);
      }
      io::write_grid(out, grid);
    }
  }
  return status;
}

}  // namespace gpugeom::cli
