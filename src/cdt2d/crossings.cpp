// Crossing segments split at their intersections (crossings.hpp).
#include "cdt2d/crossings.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <unordered_map>

#include "delaunay2d/del2d_backend.hpp"
#include "gpugeom/common.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::cdt {

namespace {
struct Piece {
  std::int32_t a, b, seg;
};
using Pair = std::pair<std::int32_t, std::int32_t>;

int orient(const double* xy, std::int32_t a, std::int32_t b, std::int32_t c) {
  double s[pred::kOrient2dScratch];
  return pred::orient2d(xy + 2 * std::int64_t(a), xy + 2 * std::int64_t(b),
                        xy + 2 * std::int64_t(c), s);
}

// Do the two pieces cross at a point inside both (each one's ends strictly on opposite sides of
// the other)? Pieces meeting at an end, touching or overlapping along one line do not.
bool cross(const double* xy, const Piece& p, const Piece& q) {
  return orient(xy, p.a, p.b, q.a) * orient(xy, p.a, p.b, q.b) < 0 &&
         orient(xy, q.a, q.b, p.a) * orient(xy, q.a, q.b, p.b) < 0;
}

// The pairs of pieces that cross, through a grid of about as many cells as pieces: each piece is
// listed in the cells its line passes (a walk from cell to cell, both neighbours taken where it
// passes a corner), and the pieces sharing a cell are tested.
std::vector<Pair> crossing_pairs(const double* xy, const std::vector<Piece>& P) {
  std::vector<Pair> out;
  if (P.size() < 2) return out;
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Piece& p : P)
    for (std::int32_t v : {p.a, p.b}) {
      x0 = std::min(x0, xy[2 * std::int64_t(v)]), x1 = std::max(x1, xy[2 * std::int64_t(v)]);
      y0 = std::min(y0, xy[2 * std::int64_t(v) + 1]),
      y1 = std::max(y1, xy[2 * std::int64_t(v) + 1]);
    }
  const std::int64_t G =
      std::clamp<std::int64_t>(std::int64_t(std::ceil(std::sqrt(double(P.size())))), 1, 4096);
  const double w = (x1 - x0) / double(G), h = (y1 - y0) / double(G);
  auto cell_of = [&](double v, double lo, double size) {
    if (!(size > 0)) return std::int64_t(0);
    return std::clamp<std::int64_t>(std::int64_t(std::floor((v - lo) / size)), 0, G - 1);
  };
  // Visits the cells of piece p (f(cell index)).
  auto walk = [&](const Piece& p, auto&& f) {
    const double ax = xy[2 * std::int64_t(p.a)], ay = xy[2 * std::int64_t(p.a) + 1];
    const double bx = xy[2 * std::int64_t(p.b)], by = xy[2 * std::int64_t(p.b) + 1];
    std::int64_t i = cell_of(ax, x0, w), j = cell_of(ay, y0, h);
    const std::int64_t ie = cell_of(bx, x0, w), je = cell_of(by, y0, h);
    const std::int64_t di = ie > i ? 1 : -1, dj = je > j ? 1 : -1;
    const double dx = bx - ax, dy = by - ay;
    // Parameters along the piece where it crosses the next vertical / horizontal cell line.
    const double tdx = dx != 0 ? std::abs(w / dx) : INFINITY,
                 tdy = dy != 0 ? std::abs(h / dy) : INFINITY;
    double tx = dx != 0 ? ((x0 + double(i + (di > 0)) * w) - ax) / dx : INFINITY;
    double ty = dy != 0 ? ((y0 + double(j + (dj > 0)) * h) - ay) / dy : INFINITY;
    for (std::int64_t steps = 0; steps <= 4 * G + 4; ++steps) {
      f(j * G + i);
      if (i == ie && j == je) return;
      if (i == ie)
        j += dj, ty += tdy;
      else if (j == je)
        i += di, tx += tdx;
      else if (tx < ty)
        i += di, tx += tdx;
      else if (ty < tx)
        j += dj, ty += tdy;
      else {  // a corner: both neighbours
        f(j * G + i + di);
        f((j + dj) * G + i);
        i += di, j += dj, tx += tdx, ty += tdy;
      }
    }
  };
  std::vector<std::int64_t> start(std::size_t(G * G + 1), 0);
  for (const Piece& p : P) walk(p, [&](std::int64_t c) { ++start[std::size_t(c) + 1]; });
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<std::int32_t> list(std::size_t(start.back()));
  std::vector<std::int64_t> at(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < P.size(); ++k)
    walk(P[k], [&](std::int64_t c) { list[std::size_t(at[std::size_t(c)]++)] = std::int32_t(k); });
  for (std::int64_t c = 0; c < G * G; ++c)
    for (std::int64_t u = start[std::size_t(c)]; u < start[std::size_t(c) + 1]; ++u)
      for (std::int64_t v = u + 1; v < start[std::size_t(c) + 1]; ++v) {
        const std::int32_t p = list[std::size_t(u)], q = list[std::size_t(v)];
        if (p != q && cross(xy, P[std::size_t(p)], P[std::size_t(q)]))
          out.push_back({std::min(p, q), std::max(p, q)});
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

struct Coord {
  double x, y;
  bool operator==(const Coord& o) const { return x == o.x && y == o.y; }
};
struct CoordHash {
  std::size_t operator()(const Coord& c) const {
    return std::hash<double>()(c.x) * 0x9e3779b97f4a7c15ull ^ std::hash<double>()(c.y);
  }
};
}  // namespace

SplitSegments split_crossings(const double* xy, std::int64_t n, const std::int32_t* segs,
                              std::int64_t m, const std::vector<Pair>& extra) {
  SplitSegments out;
  std::vector<Piece> P;
  P.reserve(std::size_t(m));
  for (std::int64_t k = 0; k < m; ++k) P.push_back({segs[2 * k], segs[2 * k + 1], std::int32_t(k)});
  std::vector<double> pts(xy, xy + 2 * n);  // the input points, then the new ones
  std::unordered_map<Coord, std::int32_t, CoordHash> vertex_at;  // new points by coordinates
  bool any = false;
  constexpr int kRounds = 4;
  for (int round = 0;; ++round) {
    std::vector<Pair> pairs = crossing_pairs(pts.data(), P);
    if (round == 0)  // (the first round's pieces are the input segments)
      for (const Pair& e : extra)
        if (e.first != e.second &&
            cross(pts.data(), P[std::size_t(e.first)], P[std::size_t(e.second)]))
          pairs.push_back({std::min(e.first, e.second), std::max(e.first, e.second)});
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    if (pairs.empty()) break;
    if (round == kRounds)
      throw Error(ErrorCode::InvalidInput,
                  "segments " + std::to_string(P[std::size_t(pairs[0].first)].seg) + " and " +
                      std::to_string(P[std::size_t(pairs[0].second)].seg) +
                      " still cross after splitting them at their rounded intersections");
    any = true;
    // The intersections, rounded; then which of them are input points (one pass over them).
    std::vector<Coord> at(pairs.size());
    std::vector<long double> tp(pairs.size()), tq(pairs.size());
    for (std::size_t e = 0; e < pairs.size(); ++e) {
      const Piece &p = P[std::size_t(pairs[e].first)], &q = P[std::size_t(pairs[e].second)];
      auto X = [&](std::int32_t v) { return (long double)pts[2 * std::size_t(v)]; };
      auto Y = [&](std::int32_t v) { return (long double)pts[2 * std::size_t(v) + 1]; };
      const long double rx = X(p.b) - X(p.a), ry = Y(p.b) - Y(p.a);
      const long double sx = X(q.b) - X(q.a), sy = Y(q.b) - Y(q.a);
      const long double den = rx * sy - ry * sx;
      const long double t = ((X(q.a) - X(p.a)) * sy - (Y(q.a) - Y(p.a)) * sx) / den;
      const long double u = ((X(q.a) - X(p.a)) * ry - (Y(q.a) - Y(p.a)) * rx) / den;
      tp[e] = std::clamp<long double>(t, 0, 1), tq[e] = std::clamp<long double>(u, 0, 1);
      at[e] = {double(X(p.a) + tp[e] * rx), double(Y(p.a) + tp[e] * ry)};
    }
    std::unordered_map<Coord, std::int32_t, CoordHash> input_at;
    for (const Coord& c : at) input_at.emplace(c, -1);
    for (std::int64_t i = 0; i < n; ++i) {
      auto it = input_at.find(Coord{xy[2 * i], xy[2 * i + 1]});
      if (it != input_at.end() && it->second < 0) it->second = std::int32_t(i);
    }
    std::vector<std::tuple<std::int32_t, long double, std::int32_t>> cuts;  // piece, t, vertex
    for (std::size_t e = 0; e < pairs.size(); ++e) {
      const Piece &p = P[std::size_t(pairs[e].first)], &q = P[std::size_t(pairs[e].second)];
      std::int32_t v = input_at[at[e]];
      if (v >= 0 && orient(pts.data(), p.a, p.b, v) == 0 && orient(pts.data(), q.a, q.b, v) == 0)
        continue;  // both run through an input point there: the recovery takes them as they are
      if (v < 0) {
        auto [it, added] = vertex_at.emplace(at[e], std::int32_t(pts.size() / 2));
        v = it->second;
        if (added) {
          if (pts.size() / 2 >= std::size_t(INT32_MAX - 1))
            throw Error(ErrorCode::InvalidInput, "too many crossings to split");
          pts.insert(pts.end(), {at[e].x, at[e].y});
          out.point_segments.insert(out.point_segments.end(),
                                    {std::min(p.seg, q.seg), std::max(p.seg, q.seg)});
        }
      }
      cuts.emplace_back(pairs[e].first, tp[e], v);
      cuts.emplace_back(pairs[e].second, tq[e], v);
    }
    if (cuts.empty()) break;
    std::sort(cuts.begin(), cuts.end());
    std::vector<Piece> next;
    next.reserve(P.size() + cuts.size());
    std::size_t c = 0;
    for (std::size_t k = 0; k < P.size(); ++k) {
      std::int32_t from = P[k].a;
      for (; c < cuts.size() && std::get<0>(cuts[c]) == std::int32_t(k); ++c) {
        const std::int32_t v = std::get<2>(cuts[c]);
        if (v != from && v != P[k].b) next.push_back({from, v, P[k].seg}), from = v;
      }
      next.push_back({from, P[k].b, P[k].seg});
    }
    P.swap(next);
  }
  if (!any || (pts.size() / 2 == std::size_t(n) && std::int64_t(P.size()) == m)) return out;
  out.points.assign(pts.begin() + 2 * n, pts.end());
  std::vector<std::int32_t> pieces_of(std::size_t(m), 0);
  for (const Piece& p : P) {
    out.pieces.insert(out.pieces.end(), {p.a, p.b});
    out.piece_segment.push_back(p.seg);
    ++pieces_of[std::size_t(p.seg)];
  }
  for (std::int32_t k : pieces_of) out.split_segments += k > 1;
  return out;
}

void check_input(std::int64_t n, const std::int32_t* segments, std::int64_t nseg,
                 const Cdt2dDomainOptions& opt) {
  del2d::check_count(n);
  if (nseg < 0 || (nseg > 0 && !segments))
    throw Error(ErrorCode::InvalidArgument,
                "segments: " + std::to_string(nseg) + " pairs given" +
                    (nseg > 0 ? " but the pointer is null" : ": the count must not be negative"));
  if (nseg > (std::int64_t(1) << 31) - 2)
    throw Error(ErrorCode::InvalidInput, "too many segments (" + std::to_string(nseg) +
                                             "): at most 2^31 - 2 per triangulation");
  for (const auto& h : opt.holes)
    if (!std::isfinite(h.x) || !std::isfinite(h.y))
      throw Error(ErrorCode::InvalidInput, "a hole point is not finite");
  for (const auto& g : opt.regions)
    if (!std::isfinite(g.x) || !std::isfinite(g.y))
      throw Error(ErrorCode::InvalidInput, "a region point is not finite");
}

void check_segment_indices(const std::int32_t* segs, std::int64_t m, std::int64_t n) {
  for (std::int64_t k = 0; k < 2 * m; ++k)
    if (segs[k] < 0 || segs[k] >= n)
      throw Error(ErrorCode::InvalidInput, "segment " + std::to_string(k / 2) + " names point " +
                                               std::to_string(segs[k]) + ", outside 0.." +
                                               std::to_string(n - 1));
}

SplitInput split_input(const double* xy, std::int64_t n, const std::int32_t* segs, std::int64_t m,
                       const SplitSegments& sp) {
  SplitInput in;
  if (sp.pieces.empty()) {
    in.points = xy, in.num_points = n;
    in.segments = segs, in.num_segments = m;
    return in;
  }
  in.joined.assign(xy, xy + 2 * n);
  in.joined.insert(in.joined.end(), sp.points.begin(), sp.points.end());
  in.points = in.joined.data(), in.num_points = std::int64_t(in.joined.size() / 2);
  in.segments = sp.pieces.data(), in.num_segments = std::int64_t(sp.pieces.size() / 2);
  return in;
}

}  // namespace gpugeom::cdt
