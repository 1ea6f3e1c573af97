// gpugeom edt: exact distance / feature transform and digital Voronoi diagram of an image or
// volume, written as .npy, with an optional PNG preview.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "cli.hpp"
#include "gpugeom/edt.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom::cli {

namespace {

template <class T>
std::vector<T> parse_list(const std::string& s, const char* what) {
  std::vector<T> v;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');) {
    char* end = nullptr;
    const double d = std::strtod(x.c_str(), &end);
    if (x.empty() || *end) throw UsageError(std::string("bad value '") + x + "' in " + what);
    v.push_back(T(d));
  }
  return v;
}

io::Grid array_grid(const std::vector<std::int64_t>& shape, io::ScalarType t, const void* p,
                    std::size_t bytes) {
  io::Grid g;
  g.shape = shape;
  g.type = t;
  g.data.assign(static_cast<const unsigned char*>(p), static_cast<const unsigned char*>(p) + bytes);
  return g;
}

// 2D preview (the first computed slice of a volume): grey distance, or coloured Voronoi cells.
void preview(const std::string& path, const EdtResult& r, bool voronoi) {
  const std::int64_t rows = r.shape[r.shape.size() - 2], cols = r.shape.back();
  std::vector<unsigned char> rgb(std::size_t(rows * cols * 3));
  double mx = 0;
  if (!voronoi)
    for (std::int64_t i = 0; i < rows * cols; ++i) mx = std::max(mx, double(r.distance64[i]));
  for (std::int64_t i = 0; i < rows * cols; ++i) {
    unsigned char* px = &rgb[i * 3];
    if (voronoi) {
      std::uint32_t h = std::uint32_t(r.labels[i]) * 2654435761u;
      h ^= h >> 15;
      px[0] = 64 + (h & 127), px[1] = 64 + ((h >> 8) & 127), px[2] = 64 + ((h >> 16) & 127);
      if (r.sqdist_int.size() && r.sqdist_int[i] == 0) px[0] = px[1] = px[2] = 0;  // the sites
    } else {
      const unsigned char v = mx > 0 ? (unsigned char)(255.0 * std::sqrt(r.distance64[i] / mx)) : 0;
      px[0] = px[1] = px[2] = v;
    }
  }
  io::write_png_rgb(path, rows, cols, rgb);
}

}  // namespace

int cmd_edt(const Global& g, Args& a) {
  if (a.help()) {
    std::cout
        << "usage: gpugeom edt IN -o OUT.npy [options]\n\n"
           "Exact Euclidean distance transform of a 2D image, a 3D volume or a grid of up to 8\n"
           "axes (.png .pgm .pbm .npy, or raw with --shape and --dtype). Writes float32 distances\n"
           "to OUT.npy.\n\n"
           "  --sites nonzero|zero  which elements are sites (default nonzero; 'zero' computes\n"
           "                        SciPy's distance_transform_edt: distance to the nearest zero)\n"
           "  --sampling a,b,...    voxel spacing per axis (C order), as in SciPy\n"
           "  --float64             write float64 distances\n"
           "  --squared FILE.npy    squared distances (int64, or float64 with --sampling)\n"
           "  --indices FILE.npy    nearest-site coordinates, int32 (ndim, *shape), SciPy's "
           "layout\n"
           "  --labels FILE.npy     nearest-site index (the digital Voronoi diagram), int32; "
           "sites\n"
           "                        are numbered in raster order; ties go to the first site in\n"
           "                        raster order\n"
           "  --preview FILE.png    look at it: grey distance field (2D, or the first slice)\n"
           "  --voronoi             make the preview the coloured Voronoi cells\n"
           "  --slices z1,z2,...    3D and up: compute only these indices along axis 0 (slice by\n"
           "                        slice: the device never holds the volume)\n"
           "  --method pba|jfa      jfa is approximate, a baseline for comparison only\n"
           "  --bands kx,ky[,kz]    PBA band counts (default: chosen by size)\n"
           "  --shape S0,S1,... --dtype T    for raw input (T: uint8 uint16 int32 float32 ...)\n";
    return kOk;
  }
  std::string out, sites = "nonzero", sampling, squared, indices, labels, prev, slices,
                   method = "pba", bands, shape, dtype;
  a.value("-o", out) || a.value("--output", out);
  a.value("--sites", sites);
  a.value("--sampling", sampling);
  a.value("--squared", squared);
  a.value("--indices", indices);
  a.value("--labels", labels);
  a.value("--preview", prev);
  a.value("--slices", slices);
  a.value("--method", method);
  a.value("--bands", bands);
  a.value("--shape", shape);
  a.value("--dtype", dtype);
  const bool f64 = a.flag("--float64"), voronoi = a.flag("--voronoi");
  auto pos = a.positionals();
  if (pos.size() != 1) throw UsageError("expected one input image or volume");
  if (out.empty() && squared.empty() && indices.empty() && labels.empty() && prev.empty())
    throw UsageError(
        "nothing to write: give -o OUT.npy and/or --squared/--indices/--labels/--preview");
  if (sites != "nonzero" && sites != "zero") throw UsageError("--sites must be nonzero or zero");
  if (method != "pba" && method != "jfa") throw UsageError("--method must be pba or jfa");
  for (const std::string* f : {&out, &squared, &indices, &labels})
    if (!f->empty() && io::extension(*f) != ".npy")
      throw UsageError("outputs are .npy files: " + *f);
  if (!prev.empty() && io::extension(prev) != ".png")
    throw UsageError("--preview writes a .png file");

  io::Grid grid;
  {
    Timer t(g, "read");
    if (io::extension(pos[0]) == ".raw" || !shape.empty()) {
      if (shape.empty() || dtype.empty()) throw UsageError("raw input needs --shape and --dtype");
      grid = io::read_raw_grid(pos[0], parse_list<std::int64_t>(shape, "--shape"),
                               io::parse_scalar(dtype));
    } else {
      grid = io::read_grid(pos[0]);
    }
  }
  EdtOptions o;
  o.backend = g.backend;
  o.method = method == "jfa" ? EdtMethod::Jfa : EdtMethod::Pba;
  if (!sampling.empty()) o.sampling = parse_list<double>(sampling, "--sampling");
  if (!slices.empty()) o.slices = parse_list<std::int64_t>(slices, "--slices");
  if (!bands.empty()) {
    auto b = parse_list<std::int64_t>(bands, "--bands");
    for (std::size_t k = 0; k < b.size() && k < 3; ++k) o.bands[k] = b[k];
  }
  o.distance = (!out.empty() || (!prev.empty() && !voronoi)) ? (f64 || !prev.empty() ? 64 : 32) : 0;
  o.squared = !squared.empty() || (voronoi && !prev.empty());
  o.features = !indices.empty();
  o.labels = !labels.empty() || voronoi;
  EdtResult r;
  {
    Timer t(g, "transform");
    r = distance_transform(grid, sites == "zero" ? SiteRule::Zero : SiteRule::NonZero, o);
  }
  if (g.verbose)
    for (auto& p : r.stats.phase_ms)
      std::fprintf(stderr, "[time]   %-10s %10.2f ms\n", p.first.c_str(), p.second);
  {
    Timer t(g, "write");
    const std::size_t n = std::size_t(r.count());
    if (!out.empty()) {
      if (o.distance == 64 && !f64) {  // float64 was computed for the preview; write float32
        std::vector<float> f(r.distance64.begin(), r.distance64.end());
        io::write_grid(out, array_grid(r.shape, io::ScalarType::F32, f.data(), n * 4));
      } else if (o.distance == 64) {
        io::write_grid(out, array_grid(r.shape, io::ScalarType::F64, r.distance64.data(), n * 8));
      } else {
        io::write_grid(out, array_grid(r.shape, io::ScalarType::F32, r.distance32.data(), n * 4));
      }
    }
    if (!squared.empty()) {
      if (!r.sqdist_int.empty())
        io::write_grid(squared,
                       array_grid(r.shape, io::ScalarType::I64, r.sqdist_int.data(), n * 8));
      else
        io::write_grid(squared,
                       array_grid(r.shape, io::ScalarType::F64, r.sqdist_real.data(), n * 8));
    }
    if (!indices.empty()) {
      std::vector<std::int64_t> s{std::int64_t(r.shape.size())};
      s.insert(s.end(), r.shape.begin(), r.shape.end());
      io::Grid ig =
          array_grid({1, 1}, io::ScalarType::I32, r.features.data(), r.features.size() * 4);
      ig.shape = s;  // (ndim, *shape): write through the npy writer, which takes any rank
      io::write_grid(indices, ig);
    }
    if (!labels.empty())
      io::write_grid(labels, array_grid(r.shape, io::ScalarType::I32, r.labels.data(), n * 4));
    if (!prev.empty()) preview(prev, r, voronoi);
  }
  if (!g.quiet)
    std::cout << "edt " << pos[0] << ": " << r.count() << " voxels on "
              << backend_name(r.stats.backend) << ", "
              << (o.method == EdtMethod::Jfa ? "JFA (approximate)" : "exact") << "\n";
  return kOk;
}

}  // namespace gpugeom::cli
