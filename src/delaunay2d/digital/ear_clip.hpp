// Ear clipping, shared by the digital method's steps that fill a hole or a pocket (the hull fill
// on the host, the shifting phase's deletions on the executor; internal). The flips that follow
// make the result Delaunay, so any triangulation of the polygon will do; this one needs only
// orientations, exact in both callers.
#pragma once
#include <cstdint>

#include "base/hd.hpp"

namespace gpugeom::del2d::digital {

// p[0..m): a simple counter-clockwise polygon (collinear runs allowed), clipped in place;
// orient(a, b, c): the sign of the orientation of its vertices a, b, c; emit(a, b, c): each
// counter-clockwise triangle cut (b leaves the polygon). An ear is a strictly convex corner with
// no other vertex inside it or on its edges. Returns how many vertices are left when no ear
// remains: fewer than 3 where the polygon was triangulated, else collinear ones (no area) or a
// polygon that was not simple. near(a, b, c, p, m, visit): calls visit(v) for every vertex of
// the polygon p[0..m) that may lie in the closed triangle (a, b, c) (and may call it for
// others), until visit returns false; the overload without it visits them all.
template <class Orient, class Emit, class Near>
GG_HD std::int64_t clip_ears(std::int32_t* p, std::int64_t m, const Orient& orient,
                             const Emit& emit, const Near& near) {
  std::int64_t i = 0, tried = 0;
  while (m >= 3 && tried < m) {
    i %= m;
    const std::int32_t a = p[(i + m - 1) % m], b = p[i], c = p[(i + 1) % m];
    bool ear = orient(a, b, c) > 0;
    if (ear)
      near(a, b, c, p, m, [&](std::int32_t v) {
        if (v != a && v != b && v != c)
          ear = !(orient(a, b, v) >= 0 && orient(b, c, v) >= 0 && orient(c, a, v) >= 0);
        return ear;
      });
    if (ear) {
      emit(a, b, c);
      for (std::int64_t j = i; j + 1 < m; ++j) p[j] = p[j + 1];
      --m, tried = 0;
    } else {
      ++i, ++tried;
    }
  }
  return m;
}

template <class Orient, class Emit>
GG_HD std::int64_t clip_ears(std::int32_t* p, std::int64_t m, const Orient& orient,
                             const Emit& emit) {
  return clip_ears(p, m, orient, emit,
                   [](std::int32_t, std::int32_t, std::int32_t, const std::int32_t* q,
                      std::int64_t k, const auto& visit) {
                     for (std::int64_t j = 0; j < k; ++j)
                       if (!visit(q[j])) return;
                   });
}

}  // namespace gpugeom::del2d::digital
