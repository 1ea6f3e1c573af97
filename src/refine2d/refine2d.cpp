// Public entries of Delaunay refinement: check the bounds and the input, split crossing segments
// where asked (cdt2d's crossings.hpp), run the rounds on the executor opt picks
// (refine2d_backend.hpp), and name the counters.
#include "gpugeom/refine2d.hpp"

#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <utility>

#include "base/stats_fields.hpp"
#include "cdt2d/crossings.hpp"
#include "delaunay2d/del2d_backend.hpp"
#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "refine2d/refine2d_backend.hpp"

namespace gpugeom {

// clang-format off
#define GG_REFINE2D_COUNTERS(X)                                                                  \
  X(rounds) X(steiner_points) X(segment_splits) X(rejected_points) X(flips) X(flip_passes)     \
  X(triangles)
// clang-format on
GG_COUNTER_MAP(Refine2dStats, GG_REFINE2D_COUNTERS);
#undef GG_REFINE2D_COUNTERS

namespace {

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

void check_options(std::int64_t n, const std::int32_t* segments, std::int64_t nseg,
                   const Refine2dOptions& opt) {
  cdt::check_input(n, segments, nseg, opt);
  if (!(opt.min_angle >= 0) || opt.min_angle > kRefineMaxAngle)
    throw Error(ErrorCode::InvalidArgument,
                "min_angle " + number(opt.min_angle) + " degrees: give 0 (no angle bound) up to " +
                    number(kRefineMaxAngle) +
                    " (above it Delaunay refinement need not end; Triangle refuses it too)");
  if (!(opt.max_area >= 0) || std::isinf(opt.max_area))
    throw Error(
        ErrorCode::InvalidArgument,
        "max_area must be a finite area > 0, or 0 for no bound (got " + number(opt.max_area) + ")");
  for (std::size_t i = 0; i < opt.regions.size(); ++i)
    if (!std::isfinite(opt.regions[i].max_area))
      throw Error(ErrorCode::InvalidArgument,
                  "region " + std::to_string(i) + ": max_area is not finite");
  const AreaGrid& g = opt.area_grid;
  if (g.rows || g.cols || !g.values.empty()) {
    if (g.rows < 1 || g.cols < 1 || std::int64_t(g.values.size()) != g.rows * g.cols)
      throw Error(ErrorCode::InvalidArgument, "area_grid: " + std::to_string(g.values.size()) +
                                                  " values for a " + std::to_string(g.rows) +
                                                  " x " + std::to_string(g.cols) + " grid");
    if (!(g.x1 > g.x0) || !(g.y1 > g.y0) || !std::isfinite(g.x1 - g.x0) ||
        !std::isfinite(g.y1 - g.y0))
      throw Error(ErrorCode::InvalidArgument,
                  "area_grid: its extent must have x1 > x0 and y1 > y0, finite");
    for (double v : g.values)
      if (!std::isfinite(v))
        throw Error(ErrorCode::InvalidArgument, "area_grid: a value is not finite");
  }
  if (opt.max_steiner_points < -1)
    throw Error(ErrorCode::InvalidArgument, "max_steiner_points must be -1 (no limit) or >= 0");
}

std::string crossing_message(std::int32_t s1, std::int32_t s2) {
  return "segments " + std::to_string(std::min(s1, s2)) + " and " +
         std::to_string(std::max(s1, s2)) +
         " cross each other at a point that is not an input point: split them there, or have "
         "them split: Crossings::Split, crossings=\"split\" in Python";
}

void set_counters(Refine2dStats& st, const refine::Tally& t, std::int64_t triangles) {
  st.rounds = t.rounds;
  st.steiner_points = t.splits + t.points;
  st.segment_splits = t.splits;
  st.rejected_points = t.rejected;
  st.flips = t.flips;
  st.flip_passes = t.flip_passes;
  st.triangles = triangles;
  // The refinement's phases first (the host entry appends its transfer after them).
  std::vector<std::pair<std::string, double>> ph = {{"triangulate", t.cdt_ms},
                                                    {"decide", t.decide_ms},
                                                    {"insert", t.insert_ms},
                                                    {"output", t.output_ms}};
  ph.insert(ph.end(), st.phase_ms.begin(), st.phase_ms.end());
  st.phase_ms = std::move(ph);
}
}  // namespace

RefinedMesh2d refine2d(const double* xy, std::int64_t n, const std::int32_t* segments,
                       std::int64_t nseg, const Refine2dOptions& opt) {
  check_options(n, segments, nseg, opt);
  cdt::check_segment_indices(segments, nseg, n);
  const Backend b = resolve_backend(opt.backend, opt.device);
  // Crossing segments split first: the pieces are the segments refined, their marks the input
  // segments they came from.
  cdt::SplitSegments sp;
  if (opt.crossings == Cdt2dOptions::Crossings::Split)
    sp = cdt::split_crossings(xy, n, segments, nseg, {});
  const cdt::SplitInput in = cdt::split_input(xy, n, segments, nseg, sp);
  std::vector<std::int32_t> final_of_base = sp.piece_segment;  // (the marks: input segments)
  if (sp.pieces.empty()) {
    final_of_base.resize(std::size_t(nseg));
    std::iota(final_of_base.begin(), final_of_base.end(), 0);
  }
  RefinedMesh2d r;
  cdt::RecoveryCounts rc;
  refine::Tally tally;
  GG_ENTRIES(b, refine).refine(in.points, in.num_points, in.segments, in.num_segments,
                               final_of_base, opt, r, rc, tally);
  if (rc.cross_a >= 0)
    throw Error(ErrorCode::InvalidInput, crossing_message(final_of_base[std::size_t(rc.cross_a)],
                                                          final_of_base[std::size_t(rc.cross_b)]));
  r.num_input_points = in.num_points;
  r.stats.backend = b;
  set_counters(r.stats, tally, r.num_triangles);
  return r;
}

DeviceRefinedMesh2d refine2d_device(const double* device_xy, std::int64_t n,
                                    const std::int32_t* device_segments, std::int64_t nseg,
                                    const Refine2dOptions& opt) {
  check_options(n, device_segments, nseg, opt);
  if (opt.crossings == Cdt2dOptions::Crossings::Split)
    throw Error(ErrorCode::InvalidArgument,
                "refine2d_device: Crossings::Split reads the segments on the host: call refine2d "
                "with host arrays for it");
  if (opt.max_area_at)
    throw Error(ErrorCode::InvalidArgument,
                "refine2d_device: max_area_at is a host function: give the sizes as an "
                "area_grid, or call refine2d");
  const Backend b = device_entry_backend(opt.backend, opt.device, "refine2d_device");
  DeviceRefinedMesh2d r;
  cdt::RecoveryCounts rc;
  refine::Tally tally;
  GG_ENTRIES(b, refine).refine_device(device_xy, n, device_segments, nseg, opt, r, rc, tally);
  if (rc.cross_a >= 0)
    throw Error(ErrorCode::InvalidInput, crossing_message(rc.cross_a, rc.cross_b));
  r.backend = r.stats.backend = b;
  set_counters(r.stats, tally, r.num_triangles);
  return r;
}

}  // namespace gpugeom
