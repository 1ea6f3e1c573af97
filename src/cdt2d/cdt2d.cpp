// Public entry of the 2D constrained Delaunay triangulation: the Delaunay triangulation on the
// executor opt picks, then the segments recovered and the Delaunay property restored on the
// host (cdt_mesh.hpp), then holes, the outside and regions (domain.hpp).
#include "gpugeom/cdt2d.hpp"

#include <cmath>
#include <string>
#include <unordered_set>

#include "base/clock.hpp"
#include "cdt2d/cdt_mesh.hpp"
#include "cdt2d/domain.hpp"
#include "gpugeom/delaunay2d.hpp"

namespace gpugeom {

ConstrainedTriangulation2d cdt2d(const double* xy, std::int64_t n, const std::int32_t* segments,
                                 std::int64_t nseg, const Cdt2dOptions& opt) {
  if (nseg < 0 || (nseg > 0 && !segments))
    throw Error(ErrorCode::InvalidArgument,
                "segments: " + std::to_string(nseg) + " pairs given" +
                    (nseg > 0 ? " but the pointer is null" : ": the count must not be negative"));
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
  Delaunay2dOptions dopt;
  static_cast<RunOptions&>(dopt) = opt;
  Triangulation2d dt = delaunay2d(xy, n, dopt);
  r.stats = dt.stats;
  double total = 0;
  for (const auto& ph : dt.stats.phase_ms) total += ph.second;
  r.stats.phase_ms = {{"delaunay", total}};
  const auto t0 = Clock::now();
  const std::int32_t* dup = dt.duplicate_of.data();
  cdt::CdtMesh mesh(xy, n, std::vector<std::int32_t>(dt.triangles.begin(), dt.triangles.end()),
                    std::vector<std::int32_t>(dt.neighbors.begin(), dt.neighbors.end()));
  std::unordered_set<std::uint64_t> seen;
  std::int64_t present = 0, recovered = 0;
  for (std::int64_t k = 0; k < nseg; ++k) {
    std::int32_t a = segments[2 * k], b = segments[2 * k + 1];
    if (dup[a] >= 0) a = dup[a];  // the point used for a repeated one
    if (dup[b] >= 0) b = dup[b];
    if (a == b) {
      ++r.zero_length_segments;
      continue;
    }
    const std::uint64_t key = a < b ? (std::uint64_t(a) << 32 | std::uint32_t(b))
                                    : (std::uint64_t(b) << 32 | std::uint32_t(a));
    if (!seen.insert(key).second) {
      ++r.repeated_segments;
      continue;
    }
    if (mesh.insert_segment(a, b, std::int32_t(k)))
      ++recovered;
    else
      ++present;
  }
  mesh.restore_delaunay();
  cdt::apply_domain(xy, n, mesh.triangles(), mesh.neighbors(), mesh.segment_of(), opt, r);
  r.duplicate_of = std::move(dt.duplicate_of);
  r.num_duplicates = dt.num_duplicates;
  r.stats.phase_ms.push_back({"constraints", ms_since(t0)});
  r.stats.counters["segments"] = nseg;
  r.stats.counters["segments_present"] = present;
  r.stats.counters["segments_recovered"] = recovered;
  r.stats.counters["segment_pieces"] = mesh.pieces();
  r.stats.counters["recovery_flips"] = mesh.recovery_flips();
  r.stats.counters["delaunay_flips"] = mesh.delaunay_flips();
  return r;
}

}  // namespace gpugeom
