// The sample's share of extreme points (convex_sample.hpp): in 2D the monotone chain with exact
// orientations (collinear points on a hull edge are not extreme), in 3D the library's hull on
// the CPU executor.
#include "blocks/convex_sample.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "gpugeom/hull3d.hpp"
#include "gpugeom/predicates.hpp"

namespace gpugeom::blocks_detail {
namespace {

// The extreme points of 2D points (distinct or not), counted by Andrew's monotone chain: the
// points sorted by x then y, each chain keeping only strict left turns.
std::int64_t extreme_points2d(std::vector<Point2> p) {
  std::sort(p.begin(), p.end(), [](const Point2& a, const Point2& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
  });
  p.erase(std::unique(p.begin(), p.end(),
                      [](const Point2& a, const Point2& b) { return a.x == b.x && a.y == b.y; }),
          p.end());
  if (p.size() < 3) return 0;
  std::vector<Point2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // the lower chain
    while (k >= 2 && orient2d(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, low = k + 1; i-- > 0;) {  // the upper chain
    while (k >= low && orient2d(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  // (the first point closes the cycle; all on one line leaves the two ends: no hull)
  return k - 1 >= 3 ? std::int64_t(k - 1) : 0;
}

}  // namespace

bool on_convex_surface(const double* pts, int dim, std::int64_t m, int threads) {
  const std::int64_t stride = convex_sample_stride(m);
  const std::int64_t s = (m + stride - 1) / stride;
  if (s < dim + 2) return false;  // (too few to tell: the split handles them)
  // (a NaN or an infinity says no: the call that follows refuses such input with its error)
  for (std::int64_t i = 0; i < s; ++i)
    for (int j = 0; j < dim; ++j)
      if (!std::isfinite(pts[dim * i * stride + j])) return false;
  std::int64_t extreme = 0;
  if (dim == 2) {
    std::vector<Point2> p(static_cast<std::size_t>(s));
    for (std::int64_t i = 0; i < s; ++i)
      p[std::size_t(i)] = {pts[2 * i * stride], pts[2 * i * stride + 1]};
    extreme = extreme_points2d(std::move(p));
  } else {
    std::vector<double> p(static_cast<std::size_t>(3 * s));
    for (std::int64_t i = 0; i < s; ++i)
      for (int j = 0; j < 3; ++j) p[std::size_t(3 * i + j)] = pts[3 * i * stride + j];
    Hull3dOptions o;
    o.backend = Backend::Cpu;
    o.threads = threads;
    try {
      extreme = convex_hull3d(p.data(), s, o).num_vertices;
    } catch (const Error& e) {
      // (flat, or coordinates the hull does not take: the call that follows says which)
      if (e.code() != ErrorCode::DegenerateInput && e.code() != ErrorCode::InvalidInput) throw;
      return false;
    }
  }
  return 2 * extreme >= s;
}

}  // namespace gpugeom::blocks_detail
