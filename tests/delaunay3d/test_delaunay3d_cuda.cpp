// The CUDA executor's 3D Delaunay tetrahedralisation: valid by the exact checker on every
// distribution and degenerate input it takes, and the same tetrahedra as the CPU executor's
// (the Delaunay tetrahedralisation of the perturbed points is unique; slot numbers and so the
// order of the output may differ).
#include <algorithm>
#include <cstdlib>
#include <string>

#include "del3d_cases.hpp"

using namespace gpugeom;

namespace {
// Under compute-sanitizer the large cases take too long: GG_DEL3D_MAX_N caps the sizes.
std::vector<std::int64_t> sizes(std::vector<std::int64_t> s) {
  if (const char* e = std::getenv("GG_DEL3D_MAX_N")) {
    const std::int64_t cap = std::atoll(e);
    s.erase(std::remove_if(s.begin(), s.end(), [&](std::int64_t n) { return n > cap; }), s.end());
  }
  return s;
}

void same_on_both(const gg_hull3d::Case& c, bool compare = true) {
  SCOPED_TRACE(c.name);
  Delaunay3dOptions o;
  o.backend = Backend::Cuda;
  const auto gpu = delaunay3d(c.pts, o);
  gg_del3d::expect_valid(c.pts, gpu);
  if (!compare) return;
  o.backend = Backend::Cpu;
  const auto cpu = delaunay3d(c.pts, o);
  EXPECT_EQ(gg_del3d::tet_set(gpu.tetrahedra), gg_del3d::tet_set(cpu.tetrahedra));
}
}  // namespace

TEST(CudaDelaunay3d, Distributions) {
  for (const auto& c : gg_hull3d::distribution_cases(sizes({5, 100, 5000, 200000}), 17)) {
    if (c.name.rfind("grid", 0) == 0) continue;  // refused in this version (see the CPU test)
    if (c.name.rfind("two_lines", 0) == 0 && c.pts.size() > 100) continue;  // (quadratic)
    same_on_both(c, c.pts.size() <= 5000);
  }
}

TEST(CudaDelaunay3d, Degenerate) {
  // (as the CPU test: many points on one hull plane may be refused, and only those)
  const std::vector<std::string> known{"grid3",      "grid4",       "grid6",           "grid9",
                                       "cube_faces", "tetra_faces", "octahedron_edges"};
  for (const auto& c : gg_hull3d::degenerate_cases()) {
    try {
      same_on_both(c);
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::Unsupported) << c.name << ": " << e.what();
      EXPECT_NE(std::find(known.begin(), known.end(), c.name), known.end()) << c.name;
    }
  }
}

TEST(CudaDelaunay3d, StarSplayingRepairs) {
  for (const char* d : {"uniform", "sphere", "thin_sphere"}) {
    const auto pts = gpugeom::generate3d(d, sizes({3000})[0], 5);
    Delaunay3dOptions o;
    o.backend = Backend::Cuda;
    o.max_flip_rounds = 1;
    gg_del3d::expect_valid(pts, delaunay3d(pts, o));
  }
}

TEST(CudaDelaunay3d, Repeatable) {  // a race would show as a different result
  const auto pts = gpugeom::generate3d("ball", sizes({100000, 5000}).front(), 3);
  Delaunay3dOptions o;
  o.backend = Backend::Cuda;
  const auto ref = gg_del3d::tet_set(delaunay3d(pts, o).tetrahedra);
  for (int r = 0; r < 3; ++r) EXPECT_EQ(gg_del3d::tet_set(delaunay3d(pts, o).tetrahedra), ref);
}
