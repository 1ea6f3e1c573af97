// The circumball of a simplex with a bound of its rounding, as gpugeom.dask's Python computes it
// (python/gpugeom/dask/_ghost.py: _circumcentres): shared by the block passes that test balls
// (the finality test, circumballs.cpp, and the border a block sends, borders.cpp), and the slabs
// of the bounds beyond a block's region that the finality test's balls must miss.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "gpugeom/blocks.hpp"

namespace gpugeom::blocks_detail {

inline constexpr double kEps = std::numeric_limits<double>::epsilon();
// As _ghost.py's _MAX_CONDITION: beyond it the centre is not trusted.
inline constexpr double kMaxCondition = 1e10;

// The boxes where points outside the region may lie: per axis and side with room, the part of
// the bounds beyond the region's face.
struct Slabs {
  int count = 0;
  double lo[6][3], hi[6][3];
};

inline Slabs slabs_of(const BlockBoxes& b, int dim) {
  Slabs s;
  for (int k = 0; k < dim; ++k)
    for (int side = 0; side < 2; ++side) {
      const bool room =
          side == 0 ? b.region_lo[k] > b.bounds_lo[k] : b.region_hi[k] < b.bounds_hi[k];
      if (!room) continue;
      for (int j = 0; j < dim; ++j) {
        s.lo[s.count][j] = b.bounds_lo[j];
        s.hi[s.count][j] = b.bounds_hi[j];
      }
      if (side == 0)
        s.hi[s.count][k] = b.region_lo[k];
      else
        s.lo[s.count][k] = b.region_hi[k];
      ++s.count;
    }
  return s;
}

// Whether the ball (c, reach) misses every slab.
inline bool misses(const Slabs& slabs, const double* c, double reach, int dim) {
  for (int s = 0; s < slabs.count; ++s) {
    double g2 = 0;
    for (int k = 0; k < dim; ++k) {
      const double gap = std::max(std::max(slabs.lo[s][k] - c[k], c[k] - slabs.hi[s][k]), 0.0);
      g2 += gap * gap;
    }
    if (!(std::sqrt(g2) > reach)) return false;
  }
  return true;
}

// The circumcentre by the adjugate (A x = rhs, rows of A the edges from vertex 0, rhs half their
// squared lengths) and the reach: the radius grown by twice a generous multiple of
// eps * cond(A) * (|x| + longest edge) and by the rounding of the centre's coordinates. False
// where the centre is not trusted.
template <int D, class I>
bool circumball(const double* pts, const I* v, double* centre, double* reach, double scale) {
  const double* p0 = pts + v[0] * D;
  double a[D][D], rhs[D], cols[D][D], det;
  for (int i = 0; i < D; ++i) {
    const double* p = pts + v[i + 1] * D;
    double sq = 0;
    for (int k = 0; k < D; ++k) {
      a[i][k] = p[k] - p0[k];
      sq += a[i][k] * a[i][k];
    }
    rhs[i] = 0.5 * sq;
  }
  if constexpr (D == 2) {
    det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    cols[0][0] = a[1][1], cols[0][1] = -a[1][0];
    cols[1][0] = -a[0][1], cols[1][1] = a[0][0];
  } else {
    auto cross = [](const double* u, const double* w, double* out) {
      out[0] = u[1] * w[2] - u[2] * w[1];
      out[1] = u[2] * w[0] - u[0] * w[2];
      out[2] = u[0] * w[1] - u[1] * w[0];
    };
    cross(a[1], a[2], cols[0]);
    cross(a[2], a[0], cols[1]);
    cross(a[0], a[1], cols[2]);
    det = a[0][0] * cols[0][0] + a[0][1] * cols[0][1] + a[0][2] * cols[0][2];
  }
  double x[D], r2 = 0, na = 0, nc = 0, edge2 = 0;
  for (int j = 0; j < D; ++j) {
    double s = 0;
    for (int i = 0; i < D; ++i) s += rhs[i] * cols[i][j];
    x[j] = s / det;
    r2 += x[j] * x[j];
  }
  for (int i = 0; i < D; ++i) {
    double e2 = 0;
    for (int k = 0; k < D; ++k) {
      e2 += a[i][k] * a[i][k];
      nc += cols[i][k] * cols[i][k];
    }
    na += e2;
    edge2 = std::max(edge2, e2);
  }
  const double radius = std::sqrt(r2);
  const double cond = std::sqrt(na) * std::sqrt(nc) / std::fabs(det);
  if (!(cond < kMaxCondition) || !std::isfinite(radius)) return false;
  const double err = 1e3 * kEps * cond * (radius + std::sqrt(edge2));
  double top = 0;
  for (int k = 0; k < D; ++k) {
    centre[k] = p0[k] + x[k];
    top = std::max(top, std::fabs(centre[k]));
  }
  *reach = radius + 2.0 * err + 64.0 * kEps * (scale + top + radius);
  return std::isfinite(*reach);
}

}  // namespace gpugeom::blocks_detail
