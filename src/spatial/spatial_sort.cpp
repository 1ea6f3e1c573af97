// Public entry of the spatial module: validates, computes the box, dispatches to a backend.
#include <cmath>
#include <limits>
#include <string>

#include "gpugeom/spatial.hpp"
#include "spatial/spatial_sort_impl.hpp"

namespace gpugeom {
namespace {

template <int D>
std::vector<std::int32_t> order_of(const double* p, std::int64_t n, Backend backend) {
  if (n > std::numeric_limits<std::int32_t>::max())
    throw Error(ErrorCode::InvalidInput, "too many points (" + std::to_string(n) +
                                             "): indices are 32-bit, at most 2147483647");
  spatial::Box box;
  for (int d = 0; d < 3; ++d) box.lo[d] = box.hi[d] = 0;
  for (int d = 0; d < D; ++d) {
    box.lo[d] = std::numeric_limits<double>::infinity();
    box.hi[d] = -box.lo[d];
  }
  bool finite = true;
  // One pass for the box and the NaN/Inf check; parallel min/max reductions.
  for (int d = 0; d < D; ++d) {
    double lo = box.lo[d], hi = box.hi[d];
#pragma omp parallel for reduction(min : lo) reduction(max : hi) reduction(&& : finite)
    for (std::int64_t i = 0; i < n; ++i) {
      double v = p[i * D + d];
      finite = finite && std::isfinite(v);
      lo = v < lo ? v : lo;
      hi = v > hi ? v : hi;
    }
    box.lo[d] = lo;
    box.hi[d] = hi;
  }
  if (!finite) throw Error(ErrorCode::InvalidInput, "point coordinates contain NaN or Inf");
  std::vector<std::int32_t> order(n);
  if (n == 0) return order;
#ifdef GPUGEOM_HAVE_CUDA
  if (resolve_backend(backend) == Backend::Cuda) {
    cuda_impl::hilbert_order(p, n, D, box, order.data());
    return order;
  }
#else
  resolve_backend(backend);  // still reports an explicit request for CUDA as unsupported
#endif
  cpu_impl::hilbert_order(p, n, D, box, order.data());
  return order;
}

}  // namespace

std::vector<std::int32_t> hilbert_order(const std::vector<Point2>& pts, Backend backend) {
  return order_of<2>(&pts.data()->x, std::int64_t(pts.size()), backend);
}
std::vector<std::int32_t> hilbert_order(const std::vector<Point3>& pts, Backend backend) {
  return order_of<3>(&pts.data()->x, std::int64_t(pts.size()), backend);
}

}  // namespace gpugeom
