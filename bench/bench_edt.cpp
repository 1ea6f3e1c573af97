// gpugeom_bench_edt: the distance transform over grid sizes and site densities on each
// backend. Reports the device-resident feature transform ("transform"), the same with the
// float32 distance and int32 label arrays computed on the device ("w/outputs"), and the whole
// call with host<->device copies ("w/copies": the caller's host grid in, host arrays out), the
// device entry point with the grid and the outputs on the device ("on_dev", CUDA), and the bus
// floor of the bytes that must cross (input bytes + output bytes at 54 GB/s, the pinned rate
// measured on the H100 machine by gpugeom_bench_bus); optionally JFA beside PBA with its error
// rate (voxels whose distance is wrong). --dist-only: float32 distances only (SciPy's
// distance_transform_edt), else distances and int32 labels. --slice-step K: 3D grids in
// slice-by-slice mode, every K-th z slice (1: all of them), the per-voxel figures then per
// computed voxel; the mode for volumes too large to hold whole. --columns packs the slices' sites
// by column (the packing of volumes past 2^32 - 2 voxels) whatever the volume's size.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "bench_csv.hpp"
#ifdef GPUGEOM_HAVE_CUDA
#include <cuda_runtime.h>
#endif
#include "exec/tuning.hpp"
#include "gpugeom/edt.hpp"
#include "gpugeom/io.hpp"

using namespace gpugeom;

namespace {
// Sites at a given density from a counter-based hash: the same grid for every backend and run.
io::Grid random_sites(const std::vector<std::int64_t>& shape, double density, std::uint64_t seed) {
  io::Grid g;
  g.shape = shape;
  g.type = io::ScalarType::U8;
  g.data.resize(std::size_t(g.count()));
  const std::uint64_t cut = std::uint64_t(density * 18446744073709551615.0);
#pragma omp parallel for
  for (std::int64_t i = 0; i < g.count(); ++i) {
    g.data[i] = bench::hash64(std::uint64_t(i), seed) < cut;
  }
  g.data[0] = 1;
  return g;
}

// --check K: K voxels drawn by hash are checked exactly against the grid itself: the label
// names a site (the label-th site in raster order), the float32 distance is that site's, and
// no site in the cube of that radius around the voxel is nearer, or as near and first in
// raster order. A complete check of those voxels, cheap at any grid size. Returns the failures.
// slices: the z slices r holds (empty: the whole grid).
std::int64_t check_sample(const io::Grid& g, const EdtResult& r, std::int64_t k,
                          const std::vector<std::int64_t>& slices) {
  const int nd = int(g.shape.size());
  std::int64_t n[3] = {1, 1, 1};  // internal x, y, z
  for (int a = 0; a < nd; ++a) n[a] = g.shape[nd - 1 - a];
  const std::int64_t rows = g.count() / n[0];
  std::vector<std::int64_t> before(std::size_t(rows) + 1, 0);  // sites before each row
#pragma omp parallel for
  for (std::int64_t row = 0; row < rows; ++row) {
    std::int64_t c = 0;
    for (std::int64_t x = 0; x < n[0]; ++x) c += g.data[std::size_t(row * n[0] + x)] != 0;
    before[std::size_t(row) + 1] = c;
  }
  for (std::int64_t row = 0; row < rows; ++row) before[row + 1] += before[row];
  std::int64_t bad = 0;
#pragma omp parallel for reduction(+ : bad)
  for (std::int64_t j = 0; j < k; ++j) {
    const std::uint64_t h = bench::hash64(std::uint64_t(j), 777);
    std::int64_t i = std::int64_t(h % std::uint64_t(g.count())), at = i;
    if (!slices.empty()) {  // a voxel of a computed slice; at: its place in the output
      const std::int64_t plane = n[0] * n[1], k = std::int64_t((h >> 40) % slices.size());
      const std::int64_t p = std::int64_t(h % std::uint64_t(plane));
      i = slices[std::size_t(k)] * plane + p, at = k * plane + p;
    }
    const std::int64_t label = r.labels[std::size_t(at)];
    const std::int64_t row =
        std::int64_t(std::upper_bound(before.begin(), before.end(), label) - before.begin()) - 1;
    std::int64_t s = -1;
    for (std::int64_t x = 0, m = before[row]; row >= 0 && row < rows && x < n[0]; ++x)
      if (g.data[std::size_t(row * n[0] + x)] && m++ == label) s = row * n[0] + x;
    if (s < 0) {
      ++bad;
      continue;
    }
    auto coords = [&](std::int64_t v, std::int64_t c[3]) {
      c[0] = v % n[0], c[1] = (v / n[0]) % n[1], c[2] = v / (n[0] * n[1]);
    };
    std::int64_t cv[3], cs[3];
    coords(i, cv);
    coords(s, cs);
    std::int64_t d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += (cs[a] - cv[a]) * (cs[a] - cv[a]);
    bool ok = r.distance32[std::size_t(at)] == float(std::sqrt(double(d2)));
    const std::int64_t R = std::int64_t(std::sqrt(double(d2))) + 1;
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
      lo[a] = std::max<std::int64_t>(0, cv[a] - R), hi[a] = std::min(n[a] - 1, cv[a] + R);
    for (std::int64_t z = lo[2]; ok && z <= hi[2]; ++z)
      for (std::int64_t y = lo[1]; ok && y <= hi[1]; ++y)
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
          const std::int64_t w = x + n[0] * (y + n[1] * z);
          if (!g.data[std::size_t(w)]) continue;
          const std::int64_t e =
              (x - cv[0]) * (x - cv[0]) + (y - cv[1]) * (y - cv[1]) + (z - cv[2]) * (z - cv[2]);
          if (e < d2 || (e == d2 && w < s)) {
            ok = false;
            break;
          }
        }
    bad += !ok;
  }
  return bad;
}
}  // namespace

int main(int argc, char** argv) {
  std::string sides = "1024,2048", dens = "0.1", backends = "all", csv, shapes;
  int dim = 2, reps = 5;
  bool jfa = false, dist_only = false, columns = false;
  std::int64_t check = 0, slice_step = 0, slice_block = 0;
  int tiles = -1;
  std::int64_t bands[3] = {0, 0, 0};
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--dim")
      dim = std::stoi(next());
    else if (a == "--sides")
      sides = next();
    else if (a == "--density")
      dens = next();
    else if (a == "--backend")
      backends = next();
    else if (a == "--reps")
      reps = std::stoi(next());
    else if (a == "--csv")
      csv = next();
    else if (a == "--jfa")
      jfa = true;
    else if (a == "--dist-only")
      dist_only = true;
    else if (a == "--check")  // K sampled voxels checked exactly (needs labels)
      check = std::stoll(next());
    else if (a == "--slice-step")  // 3D: slice by slice, every K-th slice
      slice_step = std::stoll(next());
    else if (a == "--slice-block")  // voxels of slices computed together (0: the library's)
      slice_block = std::stoll(next());
    else if (a == "--tiles")  // -1: where they pay, 0: never, 1: wherever they fit
      tiles = std::stoi(next());
    else if (a == "--columns")  // slices packed by column whatever the volume's size
      columns = true;
    else if (a == "--bands") {  // kx,ky[,kz]: PBA band counts (0: the automatic rule)
      std::stringstream bs(next());
      int k = 0;
      for (std::string x; std::getline(bs, x, ',') && k < 3; ++k) bands[k] = std::stoll(x);
    } else if (a == "--shapes")
      shapes = next();  // e.g. 4096x16384,8000x8400 (C order)
    else {
      std::cout << "usage: gpugeom_bench_edt [--dim 2|3] [--sides 1024,2048] [--density 0.1] "
                   "[--backend cpu|cuda|all] [--reps 5] [--jfa] [--dist-only] [--check K] "
                   "[--shapes 4096x16384,...] [--slice-step K] [--slice-block VOXELS] [--tiles "
                   "-1|0|1] [--columns] "
                   "[--csv FILE]\n";
      return a == "--help" ? 0 : 2;
    }
  }
  const std::vector<Backend> bks = bench::backends(backends);
  const std::string gpu = query_device().available ? query_device().name : "none";
  std::ofstream f = bench::open_bench_csv(csv);
  std::printf("# device: %s\n", gpu.c_str());
  std::printf("%-6s %-14s %8s %-5s %-4s %11s %11s %12s %10s %10s %10s\n", "edt", "grid", "density",
              "bk", "meth", "transform", "w/outputs", "w/copies", "on_dev", "bus_floor", "wrong%");
  std::vector<std::vector<std::int64_t>> all_shapes;
  if (!shapes.empty()) {
    std::stringstream ss(shapes);
    for (std::string one; std::getline(ss, one, ',');) {
      std::vector<std::int64_t> sh;
      std::stringstream parts(one);
      for (std::string x; std::getline(parts, x, 'x');) sh.push_back(std::stoll(x));
      all_shapes.push_back(sh);
    }
  } else {
    for (double side : bench::numbers(sides))
      all_shapes.push_back(std::vector<std::int64_t>(dim, std::int64_t(side)));
  }
  for (const auto& shape : all_shapes)
    for (double d : bench::numbers(dens)) {
      dim = int(shape.size());
      io::Grid g = random_sites(shape, d, 12345);
      for (Backend b : bks)
        for (int m = 0; m < (jfa ? 2 : 1); ++m) {
          EdtOptions o;
          o.backend = b;
          if (columns) {
            auto t = std::make_shared<detail::Tuning>();
            t->edt.column_packing = true;
            o.tuning = t;
          }
          // GPUGEOM_EDT_PROFILE=1: per-pass times (the library synchronises after each pass).
          o.profile = std::getenv("GPUGEOM_EDT_PROFILE") != nullptr;
          o.distance = 32;
          o.labels = !dist_only;
          o.method = m ? EdtMethod::Jfa : EdtMethod::Pba;
          for (int k = 0; k < 3; ++k) o.bands[k] = bands[k];
          o.slice_block = slice_block;
          o.tiles = tiles;
          if (slice_step > 0 && dim == 3 && m == 0)
            for (std::int64_t z = 0; z < shape[0]; z += slice_step) o.slices.push_back(z);
          std::vector<double> tt, to, tw;
          EdtResult r;
          for (int k = 0; k <= reps; ++k) {  // the first run warms up
            auto t0 = std::chrono::steady_clock::now();
            r = distance_transform(g, SiteRule::NonZero, o);
            const double w = bench::ms_since(t0);
            double t = 0, out = 0;
            for (auto& p : r.stats.phase_ms) {
              if (p.first == "transform") t = p.second;
              if (p.first == "outputs_device") out = p.second;
            }
            if (k) tt.push_back(t), to.push_back(t + out), tw.push_back(w);
          }
          std::sort(tt.begin(), tt.end());
          std::sort(to.begin(), to.end());
          std::sort(tw.begin(), tw.end());
          // Device-resident: the grid uploaded once, the outputs left on the device.
          double on_dev = -1;
#ifdef GPUGEOM_HAVE_CUDA
          if (b == Backend::Cuda && m == 0) {
            void* dg = nullptr;
            if (cudaMalloc(&dg, g.data.size()) == cudaSuccess &&
                cudaMemcpy(dg, g.data.data(), g.data.size(), cudaMemcpyHostToDevice) ==
                    cudaSuccess) {
              GridView v;
              v.data = dg;
              v.type = g.type;
              v.shape = g.shape;
              std::vector<double> td;
              for (int k = 0; k <= reps; ++k) {
                auto t0 = std::chrono::steady_clock::now();
                { const auto dr = distance_transform_device(v, SiteRule::NonZero, o); }
                if (k) td.push_back(bench::ms_since(t0));
              }
              std::sort(td.begin(), td.end());
              on_dev = td[td.size() / 2];
            }
            cudaFree(dg);
          }
#endif
          // Output bytes of the voxels computed (all of them, or the slices').
          const double out_vox =
              o.slices.empty() ? double(g.count()) : double(o.slices.size() * shape[1] * shape[2]);
          const double out_bytes = out_vox * (4.0 + (dist_only ? 0 : 4));
          const double floor_ms = (double(g.data.size()) + out_bytes) / 54e9 * 1e3;
          double wrong = 0;
          if (m) {  // JFA error rate against PBA on the same backend
            EdtOptions e = o;
            e.method = EdtMethod::Pba;
            const auto ex = distance_transform(g, SiteRule::NonZero, e);
            std::int64_t bad = 0;
            for (std::size_t i = 0; i < ex.distance32.size(); ++i)
              bad += ex.distance32[i] != r.distance32[i];
            wrong = double(bad) / double(ex.distance32.size());
          }
          if (check > 0 && !dist_only && m == 0) {
            const std::int64_t bad = check_sample(g, r, check, o.slices);
            std::printf("# check: %lld sampled voxels, %lld wrong\n", (long long)check,
                        (long long)bad);
            if (bad) return 1;
          }
          if (b == Backend::Cuda && r.stats.device_peak_bytes) {
            const double peak = double(r.stats.device_peak_bytes);
            std::printf("# device peak %.2f GB (%.2f B a computed voxel)", peak / 1e9,
                        peak / out_vox);
            if (r.stats.slices_per_block)
              std::printf(", %lld slices a block", (long long)r.stats.slices_per_block);
            std::printf("\n");
          }
          if (std::getenv("GPUGEOM_EDT_PROFILE"))
            for (auto& p : r.stats.phase_ms)
              std::printf("    %-10s %10.3f ms\n", p.first.c_str(), p.second);
          std::string grid;
          for (auto e : shape) grid += (grid.empty() ? "" : "x") + std::to_string(e);
          if (!o.slices.empty()) grid += "/" + std::to_string(slice_step);
          std::printf("%-6s %-14s %8.4f %-5s %-4s %11.3f %11.3f %12.3f %10.3f %10.3f %10.4f\n",
                      "edt", grid.c_str(), d, backend_name(b), m ? "jfa" : "pba", tt[tt.size() / 2],
                      to[to.size() / 2], tw[tw.size() / 2], on_dev, floor_ms, 100 * wrong);
          if (f)
            f << (m ? "edt_jfa" : "edt") << dim << "d,density" << d << "," << g.count() << ","
              << backend_name(b) << "," << (b == Backend::Cuda ? gpu : "cpu") << ",0,"
              << tt[tt.size() / 2] << ",0," << to[to.size() / 2] << "," << tw[tw.size() / 2] << ","
              << wrong << "\n";
        }
    }
  return 0;
}
