// Public entry of the 2D constrained Delaunay triangulation: checks the input, splits crossing
// segments where asked (crossings.hpp), then runs the Delaunay triangulation, the segment
// recovery and the domain (holes, the outside, regions) on the executor opt picks
// (cdt2d_backend.hpp).
#include "gpugeom/cdt2d.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "base/clock.hpp"
#include "base/stats_fields.hpp"
#include "cdt2d/cdt2d_backend.hpp"
#include "cdt2d/crossings.hpp"
#include "delaunay2d/del2d_backend.hpp"
#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"

namespace gpugeom {

namespace {
// The input segments that are zero-length or repeat an earlier one (ends through dup), as the
// recovery counts them when it sees the input's own segments.
void count_dropped(const std::int32_t* segs, std::int64_t m, const std::int32_t* dup,
                   ConstrainedTriangulation2d& r) {
  std::vector<std::uint64_t> keys;
  keys.reserve(std::size_t(m));
  r.zero_length_segments = 0;
  for (std::int64_t k = 0; k < m; ++k) {
    std::int32_t a = segs[2 * k], b = segs[2 * k + 1];
    if (dup[a] >= 0) a = dup[a];
    if (dup[b] >= 0) b = dup[b];
    if (a == b)
      ++r.zero_length_segments;
    else
      keys.push_back(std::uint64_t(std::min(a, b)) << 32 | std::uint32_t(std::max(a, b)));
  }
  std::sort(keys.begin(), keys.end());
  r.repeated_segments =
      std::int64_t(keys.size()) - (std::unique(keys.begin(), keys.end()) - keys.begin());
}

std::string crossing_message(std::int32_t s1, std::int32_t s2, bool split) {
  return "segments " + std::to_string(std::min(s1, s2)) + " and " +
         std::to_string(std::max(s1, s2)) +
         (split ? " still cross after splitting them at their rounded intersection"
                : " cross each other at a point that is not an input point: split them there "
                  "(add the crossing as a point and end both segments at it), or have them "
                  "split: Cdt2dOptions::Crossings::Split, crossings=\"split\" in Python, "
                  "--split on the command line");
}

// The caller's arrays need lengths known before the run; a split adds points found during it.
void refuse_into_with_split(const Cdt2dBuffers& into) {
  if (into.triangles || into.neighbors || into.segment_of || into.duplicate_of || into.attribute)
    throw Error(ErrorCode::InvalidArgument,
                "cdt2d: Cdt2dOptions::into cannot be used with Crossings::Split (the points it "
                "adds, and so the outputs' lengths, are known only after the run): leave into "
                "empty and read the result's arrays");
}

void set_counters(Cdt2dStats& st, std::int64_t nseg, const cdt::RecoveryCounts& rc,
                  const cdt::SplitSegments& sp) {
  st.segments = nseg;
  st.segments_present = rc.kept - rc.recovered;
  st.segments_recovered = rc.recovered;
  st.segment_pieces = rc.pieces;
  st.cavity_triangles = rc.cavity_triangles;
  st.cavity_antennas = rc.antennas;
  st.recovery_rounds = rc.rounds;
  st.crossings = std::int64_t(sp.points.size() / 2);
  st.segments_split = sp.split_segments;
}
}  // namespace

// clang-format off
#define GG_CDT2D_COUNTERS(X)                                                                    \
  X(segments) X(segments_present) X(segments_recovered) X(segment_pieces) X(cavity_triangles)  \
  X(cavity_antennas) X(recovery_rounds) X(crossings) X(segments_split)
// clang-format on
GG_COUNTER_MAP_OVER(Cdt2dStats, Delaunay2dStats, GG_CDT2D_COUNTERS);
#undef GG_CDT2D_COUNTERS

ConstrainedTriangulation2d cdt2d(const double* xy, std::int64_t n, const std::int32_t* segments,
                                 std::int64_t nseg, const Cdt2dOptions& opt) {
  cdt::check_input(n, segments, nseg, opt);
  cdt::check_segment_indices(segments, nseg, n);
  ConstrainedTriangulation2d r;
  const Backend b = resolve_backend(opt.backend, opt.device);
  const bool split = opt.crossings == Cdt2dOptions::Crossings::Split;
  if (split) refuse_into_with_split(opt.into);
  cdt::RecoveryCounts rc;
  cdt::SplitSegments sp;
  std::vector<std::pair<std::int32_t, std::int32_t>> known;  // crossings the recovery met
  for (int attempt = 0;; ++attempt) {
    const auto t0 = Clock::now();
    if (split) sp = cdt::split_crossings(xy, n, segments, nseg, known);
    // the input points and the new ones, when segments were split
    const cdt::SplitInput in = cdt::split_input(xy, n, segments, nseg, sp);
    if (split) r.stats.phase_ms.push_back({"crossings", ms_since(t0)});
    const auto split_ms = r.stats.phase_ms;
    rc = {};
    GG_ENTRIES(b, cdt).triangulate(in.points, in.num_points, in.segments, in.num_segments, opt, r,
                                   rc);
    if (split) r.stats.phase_ms.insert(r.stats.phase_ms.begin(), split_ms.back());
    if (rc.cross_a < 0) break;
    const bool pieces = !sp.pieces.empty();
    const std::int32_t s1 = pieces ? sp.piece_segment[std::size_t(rc.cross_a)] : rc.cross_a,
                       s2 = pieces ? sp.piece_segment[std::size_t(rc.cross_b)] : rc.cross_b;
    if (!split || attempt >= 3)
      throw Error(ErrorCode::InvalidInput, crossing_message(s1, s2, split));
    known.push_back({s1, s2});  // (the grid missed it: named from here on)
  }
  r.stats.backend = b;
  r.zero_length_segments = rc.zero_length;
  r.repeated_segments = rc.repeated;
  if (!sp.pieces.empty()) {
    // Marks name input segments; the counts of dropped segments are of the input's.
    for (auto& g : r.segment_of)
      if (g >= 0) g = sp.piece_segment[std::size_t(g)];
    r.new_points.assign(sp.points.begin(), sp.points.end());
    r.new_point_segments.assign(sp.point_segments.begin(), sp.point_segments.end());
    count_dropped(segments, nseg, r.duplicate_of.data(), r);
  }
  set_counters(r.stats, nseg, rc, sp);
  return r;
}

DeviceConstrainedTriangulation2d cdt2d_device(const double* device_xy, std::int64_t n,
                                              const std::int32_t* device_segments,
                                              std::int64_t nseg, const Cdt2dOptions& opt) {
  cdt::check_input(n, device_segments, nseg, opt);
  if (opt.crossings == Cdt2dOptions::Crossings::Split)
    throw Error(ErrorCode::InvalidArgument,
                "cdt2d_device: Crossings::Split reads the segments on the host: call cdt2d with "
                "host arrays for it");
  DeviceConstrainedTriangulation2d r;
  const Backend b = device_entry_backend(opt.backend, opt.device, "cdt2d_device");
  cdt::RecoveryCounts rc;
  GG_ENTRIES(b, cdt).triangulate_device(device_xy, n, device_segments, nseg, opt, r, rc);
  if (rc.cross_a >= 0)
    throw Error(ErrorCode::InvalidInput, crossing_message(rc.cross_a, rc.cross_b, false));
  r.backend = r.stats.backend = b;
  r.zero_length_segments = rc.zero_length;
  r.repeated_segments = rc.repeated;
  set_counters(r.stats, nseg, rc, cdt::SplitSegments{});
  return r;
}

}  // namespace gpugeom
