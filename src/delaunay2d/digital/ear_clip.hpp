// Ear clipping, shared by the digital method's steps that fill a hole or a pocket (hull_fill,
// shift; internal). The flips that follow make the result Delaunay, so any triangulation of the
// polygon will do; this one needs only orientations, exact in both callers.
#pragma once
#include <cstdint>
#include <vector>

namespace gpugeom::del2d::digital {

// p: a simple counter-clockwise polygon (collinear runs allowed); orient(a, b, c): the sign of
// the orientation of its vertices a, b, c; emit(a, b, c): each counter-clockwise triangle cut.
// An ear is a strictly convex corner with no other vertex inside it or on its edges. Returns
// what is left when no ear remains: fewer than 3 vertices, or collinear ones (no area).
template <class Orient, class Emit>
std::vector<std::int32_t> clip_ears(std::vector<std::int32_t> p, const Orient& orient,
                                    const Emit& emit) {
  std::size_t i = 0, tried = 0;
  while (p.size() >= 3 && tried < p.size()) {
    const std::size_t k = p.size();
    i %= k;
    const std::int32_t a = p[(i + k - 1) % k], b = p[i], c = p[(i + 1) % k];
    bool ear = orient(a, b, c) > 0;
    for (std::size_t j = 0; j < k && ear; ++j) {
      const std::int32_t v = p[j];
      if (v == a || v == b || v == c) continue;
      ear = !(orient(a, b, v) >= 0 && orient(b, c, v) >= 0 && orient(c, a, v) >= 0);
    }
    if (ear) {
      emit(a, b, c);
      p.erase(p.begin() + std::ptrdiff_t(i));
      tried = 0;
    } else {
      ++i, ++tried;
    }
  }
  return p;
}

}  // namespace gpugeom::del2d::digital
