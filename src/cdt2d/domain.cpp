// Holes, the outside and regions of a constrained triangulation by flood fills that stop at
// segments (domain.hpp).
#include "cdt2d/domain.hpp"

#include "gpugeom/locate.hpp"

namespace gpugeom::cdt {

namespace {
// The triangles holding each point (x, y) of pts, -1 outside the hull (exact location).
std::vector<std::int32_t> locate(const double* xy, std::int64_t n, const std::int32_t* tris,
                                 const std::int32_t* nbrs, std::int64_t nt,
                                 const std::vector<double>& pts, int threads) {
  if (pts.empty()) return {};
  const auto loc =
      find_simplex2d(xy, n, tris, nbrs, nt, pts.data(), std::int64_t(pts.size() / 2), threads);
  return std::vector<std::int32_t>(loc.begin(), loc.end());
}
}  // namespace

void apply_domain(const double* xy, std::int64_t n, const std::int32_t* tris,
                  const std::int32_t* nbrs, const std::int32_t* segs, std::int64_t nt,
                  const Cdt2dOptions& opt, ConstrainedTriangulation2d& r) {
  // Everything reachable from the seeds without crossing a segment: out[t] = value.
  auto flood = [&](const std::vector<std::int32_t>& seeds, std::vector<std::int32_t>& out,
                   std::int32_t value, const std::vector<char>* skip) {
    std::vector<std::int32_t> stack;
    for (std::int32_t t : seeds)
      if (t >= 0 && out[std::size_t(t)] < 0 && !(skip && (*skip)[std::size_t(t)]))
        out[std::size_t(t)] = value, stack.push_back(t);
    while (!stack.empty()) {
      const std::int32_t t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const std::int32_t o = nbrs[3 * std::size_t(t) + k];
        if (o < 0 || segs[3 * std::size_t(t) + k] >= 0 || out[std::size_t(o)] >= 0) continue;
        if (skip && (*skip)[std::size_t(o)]) continue;
        out[std::size_t(o)] = value;
        stack.push_back(o);
      }
    }
  };
  std::vector<std::int32_t> gone(std::size_t(nt), -1);
  std::vector<std::int32_t> seeds;
  if (opt.domain == Cdt2dOptions::Domain::Enclosed)  // from outside, across hull edges
    for (std::int64_t t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k)
        if (nbrs[3 * std::size_t(t) + k] < 0 && segs[3 * std::size_t(t) + k] < 0)
          seeds.push_back(std::int32_t(t));
  std::vector<double> pts;
  for (const auto& h : opt.holes) pts.insert(pts.end(), {h.x, h.y});
  for (std::int32_t t : locate(xy, n, tris, nbrs, nt, pts, opt.threads)) seeds.push_back(t);
  flood(seeds, gone, 1, nullptr);
  std::vector<char> removed(static_cast<std::size_t>(nt));
  for (std::int64_t t = 0; t < nt; ++t) removed[std::size_t(t)] = gone[std::size_t(t)] >= 0;
  // Regions, in order: each reaches the kept triangles no earlier region reached.
  std::vector<std::int32_t> region(std::size_t(nt), -1);
  pts.clear();
  for (const auto& g : opt.regions) pts.insert(pts.end(), {g.x, g.y});
  const auto at = locate(xy, n, tris, nbrs, nt, pts, opt.threads);
  for (std::size_t g = 0; g < at.size(); ++g) flood({at[g]}, region, std::int32_t(g), &removed);
  // Compact.
  std::vector<std::int32_t> index(std::size_t(nt), -1);
  std::int32_t kept = 0;
  for (std::int64_t t = 0; t < nt; ++t)
    if (!removed[std::size_t(t)]) index[std::size_t(t)] = kept++;
  r.removed_triangles = nt - kept;
  r.triangles.resize(3 * std::size_t(kept));
  r.neighbors.resize(3 * std::size_t(kept));
  r.segment_of.resize(3 * std::size_t(kept));
  if (!opt.regions.empty()) r.attribute.assign(std::size_t(kept), 0.0);
  for (std::int64_t t = 0; t < nt; ++t) {
    const std::int32_t i = index[std::size_t(t)];
    if (i < 0) continue;
    for (int k = 0; k < 3; ++k) {
      const std::size_t from = 3 * std::size_t(t) + k, to = 3 * std::size_t(i) + k;
      const std::int32_t o = nbrs[from];
      r.triangles[to] = tris[from];
      r.neighbors[to] = o < 0 ? -1 : index[std::size_t(o)];
      r.segment_of[to] = segs[from];
    }
    if (!opt.regions.empty() && region[std::size_t(t)] >= 0)
      r.attribute[std::size_t(i)] = opt.regions[std::size_t(region[std::size_t(t)])].attribute;
  }
}

}  // namespace gpugeom::cdt
