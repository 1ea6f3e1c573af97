// The digital sketch (sketch.hpp): grid mapping, PBA's digital Voronoi diagram, debris
// recoloured (Alg. 4.3), and the dual triangles.
#include "delaunay2d/digital/sketch.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <queue>
#include <string>
#include <tuple>

#include "delaunay2d/digital/sketch_backend.hpp"

namespace gpugeom::del2d::digital {

namespace {

// (squared distance, site raster index, pixel raster index): the order ≺.
using Key = std::tuple<std::int64_t, std::int32_t, std::int32_t>;

struct Grid {
  std::int64_t w, h;
  std::int64_t x(std::int32_t p) const { return p % w; }
  std::int64_t y(std::int32_t p) const { return p / w; }
  std::int64_t d2(std::int32_t p, std::int32_t site) const {
    const std::int64_t dx = x(p) - x(site), dy = y(p) - y(site);
    return dx * dx + dy * dy;
  }
  Key key(std::int32_t p, std::int32_t site) const { return {d2(p, site), site, p}; }
  // The up to eight neighbours of p, f(q).
  template <class F>
  void neighbours(std::int32_t p, F&& f) const {
    const std::int64_t px = x(p), py = y(p);
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        if (!dx && !dy) continue;
        const std::int64_t qx = px + dx, qy = py + dy;
        if (qx >= 0 && qy >= 0 && qx < w && qy < h) f(std::int32_t(qy * w + qx));
      }
  }
};

// A queue entry: the key of (pixel, site), the site's colour, and the pixel's place among the
// debris; the least key first.
struct Entry {
  Key key;
  std::int32_t colour, at;
  bool operator>(const Entry& o) const { return key > o.key; }
};
using MinQueue = std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>>;

}  // namespace

std::vector<std::int32_t> recolour_debris(std::int64_t w, std::int64_t h,
                                          const std::vector<std::int32_t>& debris,
                                          const std::vector<std::int32_t>& block) {
  const Grid g{w, h};
  const std::int64_t nd = std::int64_t(debris.size());
  // The debris in raster order (as the executor's compaction gives it, else sorted), and per
  // debris pixel the places of its debris neighbours (-1: not debris, so connected to its
  // site), found row by row with one search each: arrays, not hash maps (thin circles have
  // hundreds of thousands of debris pixels).
  std::vector<std::int32_t> by(static_cast<std::size_t>(nd));
  for (std::int64_t j = 0; j < nd; ++j) by[std::size_t(j)] = std::int32_t(j);
  if (!std::is_sorted(debris.begin(), debris.end()))
    std::sort(by.begin(), by.end(), [&](std::int32_t a, std::int32_t b) {
      return debris[std::size_t(a)] < debris[std::size_t(b)];
    });
  std::vector<std::int32_t> px(static_cast<std::size_t>(nd));
  for (std::int64_t t = 0; t < nd; ++t)
    px[std::size_t(t)] = debris[std::size_t(by[std::size_t(t)])];
  std::vector<std::int32_t> nb(static_cast<std::size_t>(9 * nd), -1);  // (k as in the blocks)
  for (std::int64_t t = 0; t < nd; ++t) {
    const std::int64_t ax = g.x(px[std::size_t(t)]), ay = g.y(px[std::size_t(t)]);
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      const std::int64_t y = ay + dy, x0 = std::max<std::int64_t>(ax - 1, 0),
                         x1 = std::min<std::int64_t>(ax + 1, w - 1);
      if (y < 0 || y >= h) continue;
      auto it = std::lower_bound(px.begin(), px.end(), std::int32_t(y * w + x0));
      for (; it != px.end() && *it <= y * w + x1; ++it) {
        const std::int64_t dx = g.x(*it) - ax;
        if (dx || dy)
          nb[std::size_t(9 * t + (dy + 1) * 3 + dx + 1)] = std::int32_t(it - px.begin());
      }
    }
  }
  // The colour and site pixel of the k-th block pixel around the t-th debris pixel.
  auto colour = [&](std::int64_t t, int k) {
    return block[std::size_t(18 * by[std::size_t(t)] + k)];
  };
  auto site = [&](std::int64_t t, int k) {
    return block[std::size_t(18 * by[std::size_t(t)] + 9 + k)];
  };
  auto pixel_at = [&](std::int64_t t, int k) {
    return std::int32_t((g.y(px[std::size_t(t)]) + k / 3 - 1) * w + g.x(px[std::size_t(t)]) +
                        k % 3 - 1);
  };
  std::vector<char> done(static_cast<std::size_t>(nd), 0);
  // Debris grows from the coloured neighbours nearer their site, in the order ≺.
  MinQueue q;
  for (std::int64_t t = 0; t < nd; ++t)
    for (int k = 0; k < 9; ++k) {
      if (k == 4 || colour(t, k) < 0 || nb[std::size_t(9 * t + k)] >= 0) continue;
      const std::int32_t b = pixel_at(t, k), s = site(t, k), a = px[std::size_t(t)];
      if (g.key(b, s) < g.key(a, s)) q.push({g.key(a, s), colour(t, k), std::int32_t(t)});
    }
  std::vector<std::int32_t> changed;
  while (!q.empty()) {
    const Entry e = q.top();
    q.pop();
    if (done[std::size_t(e.at)]) continue;
    done[std::size_t(e.at)] = 1;
    const std::int32_t a = std::get<2>(e.key), s = std::get<1>(e.key);
    changed.insert(changed.end(), {a, e.colour});
    for (int k = 0; k < 9; ++k) {
      const std::int32_t u = nb[std::size_t(9 * e.at + k)];
      if (u < 0 || done[std::size_t(u)]) continue;
      const std::int32_t n = px[std::size_t(u)];
      if (g.key(a, s) < g.key(n, s)) q.push({g.key(n, s), e.colour, u});
    }
  }
  return changed;
}

void set_frame(Sketch& s, const double lo[2], const double hi[2], std::int64_t side) {
  if (side < 4 || side > 46338)
    throw Error(ErrorCode::InvalidArgument,
                "digital sketch: the grid side must be 4..46338, got " + std::to_string(side));
  // Phase 1a's frame: the points go to the nearest lower-left grid point. The pixel size h is a
  // power of two and the origin a multiple of it (thesis 6.2's care for the scaling): the grid
  // points are then exact doubles, and the sketch, valid at them, can be compared exactly with
  // the points.
  const double x0 = lo[0], y0 = lo[1], x1 = hi[0], y1 = hi[1];
  const double extent = std::max(x1 - x0, y1 - y0);
  // The box spans at most `side` pixels (so [0, 1) on 1024 gets h = 2^-10); the grid keeps up
  // to two more for the origin's rounding down and the last point's pixel.
  double h = extent > 0 && std::isfinite(extent)
                 ? std::ldexp(1.0, std::ilogb(extent / double(side)))
                 : 1.0;
  while (extent / h > double(side)) h *= 2;
  s.h = h;
  s.ox = std::floor(x0 / h) * h, s.oy = std::floor(y0 / h) * h;
  auto cells = [&](double from, double to) {
    return std::clamp<std::int64_t>(std::int64_t(std::floor((to - from) / h)) + 1, 2, side + 2);
  };
  s.width = cells(s.ox, x1), s.height = cells(s.oy, y1);
  // ox + gx h is exact while |ox / h| + width stays within the doubles' 53 bits.
  // They must also stay in the range where the exact predicates are exact (predicates.hpp).
  const double lim = 0x1p52;
  s.exact = std::isfinite(s.ox) && std::isfinite(s.oy) && h >= 0x1p-142 &&
            std::abs(s.ox / h) + double(s.width) < lim &&
            std::abs(s.oy / h) + double(s.height) < lim &&
            std::abs(s.ox) + double(s.width) * h < 0x1p179 &&
            std::abs(s.oy) + double(s.height) * h < 0x1p179;
}

}  // namespace gpugeom::del2d::digital
