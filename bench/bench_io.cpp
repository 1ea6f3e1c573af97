// gpugeom_bench_io: the library's file readers and writers, MB/s per format (issue 24's I/O
// table). Points: uniform in the unit cube (3D) or square (2D); meshes: a 2D Delaunay
// triangulation of uniform points (its vertex and cell arrays as the CLI writes them).
// Each file is written, then read back (page cache warm, as a pipeline meets it), median of
// --reps; rows: format, op, n, MB, ms, MB/s.
//
//   gpugeom_bench_io [--sizes 1e6,1e7] [--reps 3] [--dir /tmp] [--formats xyz,csv,...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <omp.h>
#include <iostream>
#include <string>
#include <vector>

#include "bench_csv.hpp"
#include "gpugeom/gpugeom.hpp"

using namespace gpugeom;
namespace fs = std::filesystem;

namespace {

template <class F>
double ms_of(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void row(const std::string& fmt, const char* op, std::int64_t n, double mb, double ms) {
  std::printf("%-14s %-5s %10lld %9.1f MB %9.1f ms %8.0f MB/s\n", fmt.c_str(), op, (long long)n, mb,
              ms, mb / (ms / 1e3));
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string sizes = "1e6", dir = fs::temp_directory_path().string(),
              formats =
                  "xyz,csv,ply,ply-ascii,off,obj,node,npy,vtu,vtu-zlib,vtu-ascii,vtk,vtk-ascii,ele,"
                  "mesh-ply";
  int reps = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--sizes")
      sizes = v;
    else if (k == "--reps")
      reps = std::stoi(v);
    else if (k == "--dir")
      dir = v;
    else if (k == "--formats")
      formats = v;
    else {
      std::cerr << "unknown option " << k << "\n";
      return 2;
    }
  }
  std::vector<std::string> fmts;
  for (std::size_t a = 0, b; a < formats.size(); a = b + 1) {
    b = formats.find(',', a);
    if (b == std::string::npos) b = formats.size();
    fmts.push_back(formats.substr(a, b - a));
  }
  std::printf("# gpugeom_bench_io: %d host threads, files in %s\n", omp_get_max_threads(),
              dir.c_str());
  for (double nd : bench::numbers(sizes)) {
    const std::int64_t n = std::int64_t(nd);
    io::PointSet p3;
    p3.dim = 3;
    for (const auto& q : generate3d("uniform", n, 1))
      p3.coords.insert(p3.coords.end(), {q.x, q.y, q.z});
    io::Mesh mesh;
    bool have_mesh = false;
    for (const std::string& f : fmts) {
      const bool is_mesh =
          f.rfind("vtu", 0) == 0 || f.rfind("vtk", 0) == 0 || f == "ele" || f == "mesh-ply";
      if (is_mesh && !have_mesh) {  // a 2D triangulation of n points, made once
        std::vector<Point2> p2 = generate2d("uniform", n, 2);
        Delaunay2dOptions o;
        const auto t = delaunay2d(p2, o);
        mesh.dim = 2;
        for (const auto& q : p2) mesh.coords.insert(mesh.coords.end(), {q.x, q.y});
        mesh.cell_size = 3;
        mesh.cells.assign(t.triangles.begin(), t.triangles.begin() + 3 * t.num_triangles);
        have_mesh = true;
      }
      std::string ext = "." + f.substr(0, f.find('-'));
      if (f == "mesh-ply") ext = ".ply";
      io::WriteOptions wo;
      wo.binary = f.find("ascii") == std::string::npos;
      wo.compress = f.find("zlib") != std::string::npos;
      const std::string path = (fs::path(dir) / ("gg_bench_io" + ext)).string();
      std::vector<double> w, r;
      for (int k = 0; k < reps; ++k) {
        w.push_back(ms_of([&] {
          if (is_mesh)
            io::write_mesh(path, mesh, wo);
          else
            io::write_points(path, p3, wo);
        }));
        r.push_back(ms_of([&] {
          if (is_mesh)
            (void)io::read_mesh(path);
          else
            (void)io::read_points(path);
        }));
      }
      double mb = double(fs::file_size(path)) / 1e6;
      if (f == "ele") mb += double(fs::file_size(fs::path(path).replace_extension(".node"))) / 1e6;
      row(f, "write", n, mb, median(w));
      row(f, "read", n, mb, median(r));
      fs::remove(path);
      if (f == "ele") fs::remove(fs::path(path).replace_extension(".node"));
    }
  }
  return 0;
}
