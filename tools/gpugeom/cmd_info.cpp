// gpugeom info: what a file holds, or what GPU this machine offers.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>

#include "cli.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom::cli {

namespace {
void print_bbox(const HostVector<double>& c, int dim) {
  const char* ax = "xyz";
  std::size_t n = c.size() / dim, bad = 0;
  for (int d = 0; d < dim; ++d) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < n; ++i) {
      double v = c[i * dim + d];
      if (!std::isfinite(v)) {
        ++bad;
        continue;
      }
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    std::cout << "  " << ax[d] << " range  [" << std::setprecision(17) << lo << ", " << hi << "]\n";
  }
  if (bad) std::cout << "  warning: " << bad << " NaN/Inf coordinates\n";
}
}  // namespace

int cmd_info(const Global& g, Args& a) {
  if (a.help()) {
    std::cout << "usage: gpugeom info FILE\n       gpugeom info --device\n\n"
                 "Summarises a point, mesh or grid file (format from its extension), or shows the\n"
                 "CUDA device, its memory and which backend 'auto' picks.\n";
    return kOk;
  }
  if (a.flag("--device")) {
    DeviceInfo d = query_device();
    std::cout << "build:    "
              << (built_with_cuda() ? "with CUDA (" + built_cuda_architectures() + ")" : "CPU only")
              << "\n";
    if (d.available) {
      std::cout << "device:   " << d.name << " (compute " << d.compute_major << "."
                << d.compute_minor << ", " << d.multiprocessors << " SMs)\n"
                << "memory:   " << (d.free_memory >> 20) << " MiB free of "
                << (d.total_memory >> 20) << " MiB\n";
    } else {
      std::cout << "device:   none usable (" << d.reason << ")\n";
    }
    std::cout << "auto:     " << backend_name(resolve_backend(Backend::Auto)) << "\n";
    if (g.backend != Backend::Auto)
      std::cout << "selected: " << backend_name(resolve_backend(g.backend)) << "\n";
    return kOk;
  }
  auto pos = a.positionals();
  if (pos.size() != 1) throw UsageError("expected one file (or --device)");
  const std::string& f = pos[0];
  const std::string ext = io::extension(f);
  if (ext == ".png" || ext == ".pgm" || ext == ".pbm") {
    io::Grid gr = io::read_grid(f);
    std::cout << f << ": grid " << gr.shape[0] << " x " << gr.shape[1] << " "
              << io::scalar_name(gr.type) << "\n";
    return kOk;
  }
  if (ext == ".npy") {  // a grid, a point array or a cell array: decide by shape and type
    try {
      io::PointSet p = io::read_points(f);
      std::cout << f << ": " << p.size() << " points, " << p.dim << "D\n";
      print_bbox(p.coords, p.dim);
      return kOk;
    } catch (const Error&) {
    }
    io::Grid gr = io::read_grid(f);
    std::cout << f << ": array";
    for (auto s : gr.shape) std::cout << " " << s;
    std::cout << " " << io::scalar_name(gr.type) << "\n";
    return kOk;
  }
  if (ext == ".xyz" || ext == ".txt" || ext == ".csv" || ext == ".node") {
    io::PointSet p = io::read_points(f);
    std::cout << f << ": " << p.size() << " points, " << p.dim << "D\n";
    print_bbox(p.coords, p.dim);
    return kOk;
  }
  io::Mesh m = io::read_mesh(f);
  std::cout << f << ": " << m.num_vertices() << " vertices, " << m.dim << "D";
  if (m.num_cells())
    std::cout << ", " << m.num_cells() << (m.cell_size == 3 ? " triangles" : " tetrahedra");
  std::cout << "\n";
  print_bbox(m.coords, m.dim);
  return kOk;
}

}  // namespace gpugeom::cli
