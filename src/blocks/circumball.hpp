// The circumball of a simplex with a bound of its rounding, as gpugeom.dask's Python computes it
// (python/gpugeom/dask/_ghost.py: _circumcentres): shared by the block passes that test balls
// (the finality test, circumballs.cpp, and the border a block sends, simplex_rules.hpp) on either
// executor, and the slabs of the bounds beyond a block's region that the finality test's balls
// must miss.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "base/hd.hpp"
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
GG_HD inline bool misses(const Slabs& slabs, const double* c, double reach, int dim) {
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

// A circumball as it was computed: vertex 0 (p0), the centre relative to it (x, the solution
// of A x = rhs, rows of A the edges from vertex 0, rhs half their squared lengths) and a bound
// of x's error (err: twice a generous multiple of eps * cond(A) * (|x| + longest edge)).
struct BallParts {
  const double* p0;
  double x[3];
  double radius, err;
};

// The circumcentre by the adjugate; false where it is not trusted (cond(A) past
// kMaxCondition, or not finite).
template <int D, class I>
GG_HD bool circumball_parts(const double* pts, const I* v, BallParts* b) {
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
  double r2 = 0, na = 0, nc = 0, edge2 = 0;
  b->p0 = p0;
  for (int j = 0; j < D; ++j) {
    double s = 0;
    for (int i = 0; i < D; ++i) s += rhs[i] * cols[i][j];
    b->x[j] = s / det;
    r2 += b->x[j] * b->x[j];
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
  b->radius = std::sqrt(r2);
  const double cond = std::sqrt(na) * std::sqrt(nc) / std::fabs(det);
  if (!(cond < kMaxCondition) || !std::isfinite(b->radius)) return false;
  b->err = 2.0 * 1e3 * kEps * cond * (b->radius + std::sqrt(edge2));
  return true;
}

// The centre and the reach: the radius grown by the centre's error bound and by the rounding of
// the centre's coordinates. False where the centre is not trusted.
template <int D>
GG_HD bool centre_and_reach(const BallParts& b, double scale, double* centre, double* reach) {
  double top = 0;
  for (int k = 0; k < D; ++k) {
    centre[k] = b.p0[k] + b.x[k];
    top = std::max(top, std::fabs(centre[k]));
  }
  *reach = b.radius + b.err + 64.0 * kEps * (scale + top + b.radius);
  return std::isfinite(*reach);
}
template <int D, class I>
GG_HD bool circumball(const double* pts, const I* v, double* centre, double* reach, double scale) {
  BallParts b;
  return circumball_parts<D>(pts, v, &b) && centre_and_reach<D>(b, scale, centre, reach);
}

// Whether the ball may hold a point of the closed box [lo, hi] grown by `margin`, by the ball's
// own function f(q) = |q - p0|^2 - 2 x.(q - p0), at most 0 exactly in the ball: its least
// value over the box (per axis, at x clamped to the box's span from p0) against the bound of
// x's error over the box (2 err |q - p0|) and of the rounding. Much tighter than the reach for
// the flat simplices along the hull: there the centre is far and its error, times the radius,
// spans the whole bounds, while f's error stays that of x times the box's distance from p0.
template <int D>
GG_HD bool may_meet(const BallParts& b, const double* lo, const double* hi, double margin) {
  double f = 0, far2 = 0, mag = 0;
  for (int j = 0; j < D; ++j) {
    const double s = lo[j] - margin - b.p0[j], e = hi[j] + margin - b.p0[j];
    const double d = std::min(std::max(b.x[j], s), e);
    f += d * (d - 2.0 * b.x[j]);
    mag += d * d + 2.0 * std::fabs(b.x[j] * d);
    const double far = std::max(std::fabs(s), std::fabs(e));
    far2 += far * far;
  }
  return !(f > 2.0 * b.err * std::sqrt(far2) * (1.0 + 8.0 * kEps) + 16.0 * kEps * mag);
}

// The same for one point q.
template <int D>
GG_HD bool may_hold(const BallParts& b, const double* q) {
  double f = 0, d2 = 0, mag = 0;
  for (int j = 0; j < D; ++j) {
    const double d = q[j] - b.p0[j];
    f += d * (d - 2.0 * b.x[j]);
    d2 += d * d;
    mag += d * d + 2.0 * std::fabs(b.x[j] * d);
  }
  return !(f > 2.0 * b.err * std::sqrt(d2) * (1.0 + 8.0 * kEps) + 16.0 * kEps * mag);
}

}  // namespace gpugeom::blocks_detail
