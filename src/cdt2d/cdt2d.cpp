// Public entry of the 2D constrained Delaunay triangulation: checks the input, runs the Delaunay
// triangulation and the segment recovery on the executor opt picks (cdt2d_backend.hpp), then
// removes holes and the outside and spreads regions on the host (domain.hpp).
#include "gpugeom/cdt2d.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "base/clock.hpp"
#include "cdt2d/cdt2d_backend.hpp"
#include "cdt2d/domain.hpp"
#include "delaunay2d/del2d_backend.hpp"
#include "exec/dispatch.hpp"

namespace gpugeom {

ConstrainedTriangulation2d cdt2d(const double* xy, std::int64_t n, const std::int32_t* segments,
                                 std::int64_t nseg, const Cdt2dOptions& opt) {
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
  for (std::int64_t k = 0; k < 2 * nseg; ++k)
    if (segments[k] < 0 || segments[k] >= n)
      throw Error(ErrorCode::InvalidInput, "segment " + std::to_string(k / 2) + " names point " +
                                               std::to_string(segments[k]) + ", outside 0.." +
                                               std::to_string(n - 1));
  ConstrainedTriangulation2d r;
  const Backend b = resolve_backend(opt.backend, opt.device);
  cdt::RecoveryCounts rc;
  GG_ON_EXECUTOR(b, cdt, triangulate, xy, n, segments, nseg, opt, r, rc);
  r.stats.backend = b;
  r.zero_length_segments = rc.zero_length;
  r.repeated_segments = rc.repeated;
  if (opt.domain != Cdt2dOptions::Domain::ConvexHull || !opt.holes.empty() ||
      !opt.regions.empty()) {
    const auto t0 = Clock::now();
    const HostVector<std::int32_t> tris = std::move(r.triangles), nbrs = std::move(r.neighbors),
                                   segs = std::move(r.segment_of);
    cdt::apply_domain(xy, n, tris.data(), nbrs.data(), segs.data(), std::int64_t(tris.size() / 3),
                      opt, r);
    r.stats.phase_ms.push_back({"domain", ms_since(t0)});
  }
  r.stats.counters["segments"] = nseg;
  r.stats.counters["segments_present"] = rc.kept - rc.recovered;
  r.stats.counters["segments_recovered"] = rc.recovered;
  r.stats.counters["segment_pieces"] = rc.pieces;
  r.stats.counters["cavity_triangles"] = rc.cavity_triangles;
  r.stats.counters["cavity_antennas"] = rc.antennas;
  r.stats.counters["recovery_rounds"] = rc.rounds;
  return r;
}

}  // namespace gpugeom
