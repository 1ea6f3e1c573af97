// The boundary test of the digital method's shifting phase and of its start's check (issue 20;
// internal), on the host and the executor alike: exact orientations of doubles.
#pragma once
#include "base/hd.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::del2d::digital {

GG_HD inline int orient(const double* a, const double* b, const double* c) {
  double s[pred::kOrient2dScratch];
  return pred::orient2d(a, b, c, s);
}

// Does the boundary turn left or go straight on at b (a -> b -> c)? Straight on means b lies
// strictly between a and c; a turn back (c on the ray towards a) is no convex turn.
GG_HD inline bool convex_turn(const double* a, const double* b, const double* c) {
  const int o = orient(a, b, c);
  if (o != 0) return o > 0;
  auto between = [](double u, double v, double w) { return (u < v && v < w) || (u > v && v > w); };
  return between(a[0], b[0], c[0]) || (a[0] == b[0] && b[0] == c[0] && between(a[1], b[1], c[1]));
}

}  // namespace gpugeom::del2d::digital
