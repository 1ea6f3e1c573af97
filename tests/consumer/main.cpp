#include <gpugeom/gpugeom.hpp>

#include <cstdio>

int main() {
  auto pts = gpugeom::generate3d("ball", 1000, 7);
  auto order = gpugeom::hilbert_order(pts, gpugeom::Backend::Cpu);
  int o = gpugeom::orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  std::printf("consumer: %zu points sorted, orient3d = %d\n", order.size(), o);
  return order.size() == 1000 && o == 1 ? 0 : 1;
}
