// The digital sketch (sketch.hpp): grid mapping, PBA's digital Voronoi diagram, debris
// recoloured (Alg. 4.3), and the dual triangles.
#include "delaunay2d/digital/sketch.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <queue>
#include <string>
#include <tuple>
#include <unordered_map>

#include "delaunay2d/digital/sketch_backend.hpp"
#include "exec/dispatch.hpp"

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

// A min-queue of (key, site) pairs.
using Entry = std::pair<Key, std::int32_t>;  // (key of (pixel, site), site's pixel)
using MinQueue = std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>>;

}  // namespace

std::vector<std::int32_t> recolour_debris(std::int64_t w, std::int64_t h,
                                          const std::vector<std::int32_t>& pixel,
                                          std::vector<std::int32_t>& colour,
                                          const std::vector<std::int32_t>& cand) {
  const Grid g{w, h};
  // Among the candidates, those 8-connected through their colour to a pixel that is not one
  // (connected to its site) are connected too; the rest are the debris.
  std::unordered_map<std::int32_t, char> state;  // candidate -> connected?
  state.reserve(cand.size() * 2);
  for (std::int32_t a : cand) state[a] = 0;
  auto connected = [&](std::int32_t p) {
    const auto it = state.find(p);
    return it == state.end() || it->second;
  };
  {
    std::vector<std::int32_t> stack;
    for (std::int32_t a : cand) {
      bool seed = false;
      g.neighbours(a, [&](std::int32_t b) {
        seed |= colour[std::size_t(b)] == colour[std::size_t(a)] && !state.count(b);
      });
      if (seed && !state[a]) state[a] = 1, stack.push_back(a);
      while (!stack.empty()) {
        const std::int32_t p = stack.back();
        stack.pop_back();
        g.neighbours(p, [&](std::int32_t b) {
          const auto it = state.find(b);
          if (it != state.end() && !it->second && colour[std::size_t(b)] == colour[std::size_t(p)])
            it->second = 1, stack.push_back(b);
        });
      }
    }
  }
  // Alg. 4.3: debris grows from the coloured neighbours nearer their site, in the order ≺.
  MinQueue q;
  for (std::int32_t a : cand) {
    if (connected(a)) continue;
    g.neighbours(a, [&](std::int32_t b) {
      if (!connected(b)) return;
      const std::int32_t site = pixel[std::size_t(colour[std::size_t(b)])];
      if (g.key(b, site) < g.key(a, site)) q.push({g.key(a, site), site});
    });
  }
  std::vector<std::int32_t> changed;
  while (!q.empty()) {
    const auto [k, site] = q.top();
    q.pop();
    const std::int32_t a = std::get<2>(k);
    if (connected(a)) continue;
    state[a] = 1;
    colour[std::size_t(a)] = colour[std::size_t(site)];
    changed.insert(changed.end(), {a, colour[std::size_t(a)]});
    g.neighbours(a, [&](std::int32_t c) {
      if (!connected(c) && g.key(a, site) < g.key(c, site)) q.push({g.key(c, site), site});
    });
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

Sketch digital_sketch(const double* xy, std::int64_t n, std::int64_t side, const RunOptions& run,
                      bool keep_colour) {
  Sketch s;
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (std::int64_t i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d)
      lo[d] = std::min(lo[d], xy[2 * i + d]), hi[d] = std::max(hi[d], xy[2 * i + d]);
  set_frame(s, lo, hi, side);
  const Backend b = resolve_backend(run.backend, run.device);
  GG_ON_EXECUTOR(b, del2d, digital_sketch_dual, xy, n, run, keep_colour, s);
  return s;
}

}  // namespace gpugeom::del2d::digital
