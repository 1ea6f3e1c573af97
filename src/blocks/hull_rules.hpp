// The 2D hull filter's rules (hull_candidates2d in hull_filter.cpp on host threads, and
// hull_filter_on.hpp on an executor): the extreme point in each of 8 directions, the polygon they
// make, and a point strictly inside it by a margin above the rounding of its orientations, so
// that what is not strictly inside is a superset of the hull's extreme points.
#pragma once
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "base/hd.hpp"

namespace gpugeom::blocks_detail {

// Shewchuk's bound on the rounding of a 2D orientation computed in doubles, relative to the sum
// of its two products' magnitudes (ccwerrboundA; epsilon is half an ulp of 1).
constexpr double kOrientBoundEps = std::numeric_limits<double>::epsilon() / 2;
constexpr double kOrientBound = (3.0 + 16.0 * kOrientBoundEps) * kOrientBoundEps;

// The 8 directions, counter-clockwise from +x.
struct Directions8 {
  double x[8], y[8];
  Directions8() {
    const double pi = std::acos(-1.0);
    for (int k = 0; k < 8; ++k) x[k] = std::cos(2 * pi * k / 8), y[k] = std::sin(2 * pi * k / 8);
  }
};

// The polygon of the extreme points best[8] (counter-clockwise, repeats dropped); fewer than 3
// vertices: none (every point is then a candidate).
inline std::vector<std::int64_t> octagon(const std::int64_t* best) {
  std::vector<std::int64_t> poly;
  for (int k = 0; k < 8; ++k)
    if (poly.empty() || poly.back() != best[k]) poly.push_back(best[k]);
  if (poly.size() > 1 && poly.front() == poly.back()) poly.pop_back();
  if (poly.size() < 3) poly.clear();
  return poly;
}

// Whether (x, y) lies strictly inside the counter-clockwise polygon of m vertices (2 coordinates
// each), by more than the rounding of each edge's orientation.
GG_HD inline bool strictly_inside(double x, double y, const double* poly, int m) {
  for (int e = 0; e < m; ++e) {
    const double* a = poly + 2 * e;
    const double* b = poly + 2 * ((e + 1) % m);
    const double left = (a[0] - x) * (b[1] - y), right = (a[1] - y) * (b[0] - x);
    if (!(left - right > kOrientBound * (fabs(left) + fabs(right)))) return false;
  }
  return true;
}

}  // namespace gpugeom::blocks_detail
