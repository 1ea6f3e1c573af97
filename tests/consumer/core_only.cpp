// The core without gpugeom_io (issue 48): the grid capabilities' headers must not include
// gpugeom/io.hpp, and the core must link without the file readers. The definition of io::Grid
// below would collide with io.hpp's had any header here included it.
#include <gpugeom/cvd.hpp>
#include <gpugeom/delaunay2d.hpp>
#include <gpugeom/edt.hpp>
#include <gpugeom/grid_view.hpp>

#include <cstdint>
#include <cstdio>
#include <vector>

namespace gpugeom::io {
struct Grid {
  int not_the_library_grid = 0;
};
}  // namespace gpugeom::io

int main() {
  std::vector<std::uint8_t> mask(64 * 64, 1);
  mask[0] = 0;
  gpugeom::EdtOptions o;
  o.backend = gpugeom::Backend::Cpu;
  const gpugeom::GridView g{mask.data(), gpugeom::ScalarType::U8, {64, 64}};
  const auto d = gpugeom::distance_transform(g, gpugeom::SiteRule::Zero, o);
  const std::vector<double> xy = {0, 0, 1, 0, 0, 1, 1, 1};
  gpugeom::Delaunay2dOptions t;
  t.backend = gpugeom::Backend::Cpu;
  const auto tri = gpugeom::delaunay2d(xy.data(), 4, t);
  std::printf("consumer_core: %lld distances, %zu triangles\n", (long long)d.count(),
              tri.num_triangles);
  return d.count() == 64 * 64 && tri.num_triangles == 2 ? 0 : 1;
}
