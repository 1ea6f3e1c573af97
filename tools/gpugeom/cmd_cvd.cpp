// gpugeom cvd: a weighted centroidal Voronoi diagram of a density image or volume; writes the
// sites as points, optionally their masses and a coloured preview of the cells.
#include <cmath>
#include <cstring>
#include <iostream>

#include "cvd_cli.hpp"
#include "gpugeom/edt.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom::cli {

namespace {

// The cells of the sites (rounded to pixels) over the first slice, coloured, sites in black.
void preview(const std::string& path, const io::Grid& density, const CvdResult& r) {
  const int nd = r.dim;
  const std::int64_t rows = density.shape[nd - 2], cols = density.shape[nd - 1];
  std::vector<std::int64_t> shape{rows, cols}, sites;
  std::vector<std::int32_t> index;  // preview site -> CVD site
  for (std::int64_t i = 0; i < r.num_sites; ++i) {
    if (nd == 3 && std::lround(r.sites[i * 3 + 2]) != 0) continue;  // slice 0 only
    sites.push_back(std::lround(r.sites[i * nd + 1]));
    sites.push_back(std::lround(r.sites[i * nd]));
    index.push_back(std::int32_t(i));
  }
  if (index.empty()) throw UsageError("--preview: no site lies in the first slice");
  EdtOptions o;
  o.labels = true;
  o.squared = true;
  const EdtResult v = distance_transform_sites(shape, sites, o);
  double mx = 0;
  for (std::int64_t i = 0; i < rows * cols; ++i) mx = std::max(mx, density.value(i));
  std::vector<unsigned char> rgb(std::size_t(rows * cols * 3));
  for (std::int64_t i = 0; i < rows * cols; ++i) {
    std::uint32_t h = std::uint32_t(index[v.labels[i]]) * 2654435761u;
    h ^= h >> 15;
    const double shade = 0.45 + 0.55 * density.value(i) / mx;  // darker where denser
    unsigned char* px = &rgb[i * 3];
    for (int k = 0; k < 3; ++k)
      px[k] = (unsigned char)(255 - shade * (40 + ((h >> (8 * k)) & 127)));
    if (v.sqdist_int[i] == 0) px[0] = px[1] = px[2] = 0;
  }
  io::write_png_rgb(path, rows, cols, rgb);
}

}  // namespace

int cmd_cvd(const Global& g, Args& a) {
  if (a.help()) {
    std::cout << "usage: gpugeom cvd DENSITY -n N -o SITES [options]\n\n"
                 "Weighted centroidal Voronoi diagram of a 2D density image or 3D volume (.png\n"
                 ".pgm .npy; values >= 0): Lloyd's iteration from N sites drawn with probability\n"
                 "proportional to the density (or --initial). Writes the sites as points\n"
                 "(.xyz .txt .csv .ply .npy ...), x = column, y = row[, z = slice], in pixels.\n\n"
                 "  -n N                  number of sites\n"
                 "  --initial POINTS      start from these sites instead\n"
              << kLloydHelp
              << "  --mass FILE.npy       each site's cell mass (sum of the density), float64\n"
                 "  --energy FILE.csv     the energy of every iteration\n"
                 "  --preview FILE.png    the cells (first slice of a volume) for a person to "
                 "look at\n";
    return kOk;
  }
  std::string out, n, initial, mass, energy, prev;
  a.value("-o", out) || a.value("--output", out);
  a.value("-n", n);
  a.value("--initial", initial);
  a.value("--mass", mass);
  a.value("--energy", energy);
  a.value("--preview", prev);
  CvdOptions o;
  o.backend = g.backend;
  read_lloyd_options(a, o);
  auto pos = a.positionals();
  if (pos.size() != 1) throw UsageError("expected one density image or volume");
  if (out.empty()) throw UsageError("give -o SITES (a point file: .xyz .ply .npy ...)");
  if (n.empty() == initial.empty()) throw UsageError("give either -n N or --initial POINTS");
  if (!mass.empty() && io::extension(mass) != ".npy") throw UsageError("--mass writes a .npy file");
  if (!prev.empty() && io::extension(prev) != ".png") throw UsageError("--preview writes a .png");
  io::Grid density;
  {
    Timer t(g, "read");
    density = io::read_grid(pos[0]);
  }
  const int nd = int(density.shape.size());
  if (!n.empty()) o.num_sites = to_count(n, "-n");
  if (!initial.empty()) {
    const io::PointSet p = io::read_points(initial);
    if (p.dim != nd)
      throw UsageError("--initial has " + std::to_string(p.dim) + "D points for a " +
                       std::to_string(nd) + "D density");
    o.initial_sites.assign(p.coords.begin(), p.coords.end());
  }
  attach_progress(g, o);
  CvdResult r;
  {
    Timer t(g, "lloyd");
    r = centroidal_voronoi(density, o);
  }
  finish_progress(g, r);
  {
    Timer t(g, "write");
    io::PointSet p;
    p.dim = r.dim;
    p.coords.assign(r.sites.begin(), r.sites.end());
    io::write_points(out, p);
    if (!mass.empty()) {
      io::Grid m;
      m.shape = {r.num_sites};
      m.type = io::ScalarType::F64;
      m.data.resize(r.mass.size() * 8);
      std::memcpy(m.data.data(), r.mass.data(), m.data.size());
      io::write_grid(mass, m);
    }
    if (!energy.empty()) {
      std::string csv = "iteration,energy\n";
      for (std::size_t i = 0; i < r.energy.size(); ++i)
        csv += std::to_string(i + 1) + "," + std::to_string(r.energy[i]) + "\n";
      io::write_text(energy, csv);
    }
    if (!prev.empty()) preview(prev, density, r);
  }
  if (!g.quiet)
    std::cout << "cvd " << pos[0] << ": " << r.num_sites << " sites, " << r.iterations
              << " iterations, energy " << r.energy.back() << "\n";
  return kOk;
}

}  // namespace gpugeom::cli
