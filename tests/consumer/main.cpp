#include <gpugeom/gpugeom.hpp>

#include <cstdio>

int main() {
  auto pts = gpugeom::generate3d("ball", 1000, 7);
  auto order = gpugeom::hilbert_order(pts, gpugeom::Backend::Cpu);
  int o = gpugeom::orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  // the files (gpugeom_io): points parsed from memory as read_points reads a file
  const auto cloud = gpugeom::io::parse_points("0 0 0\n1 0 0\n0 1 0\n", ".xyz", "mem.xyz");
  std::printf("consumer: %zu points sorted, orient3d = %d, %zu points parsed\n", order.size(), o,
              cloud.size());
  return order.size() == 1000 && o == 1 && cloud.size() == 3 ? 0 : 1;
}
