/// @file
/// Quality triangular meshes of a 2D domain by Delaunay refinement (issue 50): Triangle's -q and
/// -a on the executor.
///
/// refine2d starts from the constrained Delaunay triangulation of points and segments (cdt2d.hpp:
/// the same holes, regions, domain and crossing rules) and adds Steiner points in parallel rounds
/// until every triangle has its smallest angle at least min_angle and its area at most the bound
/// that applies to it. The input's triangulation is made once and kept; each round, in parallel:
///   * splits every subsegment encroached upon (a vertex in its diametral lens, Triangle's test);
///   * gives each bad triangle its new point: Ungor's off-centre for a small angle (the point on
///     the bisector of the shortest edge that makes that edge's new triangle just good, or the
///     circumcentre when nearer), the circumcentre for a large area; a point a segment hides from
///     its triangle, or one in the lens of a subsegment next to where it lands, is rejected and
///     splits that subsegment instead (no point is ever removed, as in Triangle);
///   * inserts the splits, then the new points whose cavities no better-ranked point touches (the
///     worst triangles first, so the points of one round never crowd each other), and restores
///     the constrained Delaunay property by exact flips.
/// Subsegments at an input vertex where segments meet are split on concentric shells (at powers
/// of two from the vertex, Ruppert's and Shewchuk's rule), and a triangle whose smallest angle is
/// an input angle between two segments, or whose shortest edge joins two shell vertices of such a
/// corner, is left as it is (Shewchuk's terminator): those are the small angles the input forces,
/// reported in `small_angles` with the reason. Without Domain::Enclosed the convex hull's edges
/// are taken as segments (Triangle's -c). The result is the same on every executor and thread
/// count: each round's choices are functions of the exact triangulation and of arithmetic that
/// rounds the same way on both.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gpugeom/cdt2d.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

/// The largest smallest-angle bound accepted (Triangle's: above it refinement need not end).
constexpr double kRefineMaxAngle = 33.8;

/// A sizing field given as samples on a regular grid: values[r * cols + c] is the largest area
/// allowed at (x0 + c * (x1 - x0) / (cols - 1), y0 + r * (y1 - y0) / (rows - 1)), bilinear in
/// between and clamped to the grid outside it. A triangle is too large when its area exceeds the
/// field at its centroid.
struct AreaGrid {
  std::vector<double> values;
  std::int64_t rows = 0, cols = 0;
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
};

/// The caller's arrays for refine2d's outputs (Refine2dOptions::into; each optional): host memory
/// for refine2d, device memory for refine2d_device (host memory where it runs on the CPU
/// executor). Every length depends on the result: points at least 2 * num_points, triangles,
/// neighbors and segment_of at least 3 * num_triangles, duplicate_of at least num_points,
/// attribute (with regions) at least num_triangles, subsegments at least 2 * num_subsegments and
/// subsegment_of at least num_subsegments. They are checked once the counts are known and before
/// anything is written (Error(InvalidArgument) naming the array and both lengths): size them for
/// the Steiner points you allow (max_steiner_points) or retry with the counts the error gives. An
/// output written into a caller's array is empty (null) in the result; the counts say how much
/// of it was written.
struct Refine2dBuffers {
  OutBuffer<double> points, attribute;
  OutBuffer<std::int32_t> triangles, neighbors, segment_of, duplicate_of, subsegments,
      subsegment_of;
};

/// How refine2d meshes a domain: the smallest angle, the largest area (a number, per region or a
/// function), the Steiner point limit, the domain's options (Cdt2dDomainOptions) and the caller's
/// arrays.
struct Refine2dOptions : Cdt2dDomainOptions {
  Refine2dBuffers into;  ///< optional
  /// Degrees, 0 < min_angle <= kRefineMaxAngle; 0 turns the angle bound off (-a alone).
  double min_angle = 20;
  /// The largest triangle area anywhere (0: none); per region, Cdt2dRegion::max_area.
  double max_area = 0;
  AreaGrid area_grid;  ///< (empty: none)
  /// A sizing function of position, called on the host at triangle centroids (host entry only):
  /// the largest area allowed there (<= 0 or not finite: no bound).
  std::function<double(double, double)> max_area_at;
  /// Triangle's -S: at most this many Steiner points (-1: no limit); the bad triangles left are
  /// reported in small_angles / large_triangles.
  std::int64_t max_steiner_points = -1;
};

/// Why a triangle kept an angle below the bound.
enum class SmallAngle : std::int8_t {
  InputAngle = 1,  ///< its smallest angle lies between two segments at an input vertex
  Shell = 2,       ///< its shortest edge joins the two shell vertices of a small input angle
  Limit = 3,       ///< max_steiner_points was reached, or no double lies where the point belongs
};

/// Statistics of a quality mesh: RunStats (phases "triangulate" (the input's constrained
/// triangulation), "decide" and "insert" (the rounds' two steps: what goes in; inserting it and
/// flipping), "output", then "refine" (all of them) and "to_host") and the counters.
struct Refine2dStats : RunStats {
  /// Refinement rounds, and the Steiner points inserted (segment splits among them).
  std::int64_t rounds = 0, steiner_points = 0, segment_splits = 0;
  /// New points not inserted because they would encroach upon a subsegment (which is split
  /// instead).
  std::int64_t rejected_points = 0;
  /// Edge flips, and the flip passes they took.
  std::int64_t flips = 0, flip_passes = 0;
  /// Triangles of the mesh.
  std::int64_t triangles = 0;

  std::map<std::string, std::int64_t> counter_map() const override;
};

/// The result of refine2d: points (input and Steiner), triangles, neighbours, segments and the
/// triangles the bounds could not reach, in host memory.
struct RefinedMesh2d {
  /// Every vertex, x and y: the input points (their indices kept; with Crossings::Split the
  /// crossing vertices follow them), then the Steiner points in the order they were added.
  HostVector<double> points;
  std::int64_t num_input_points = 0;  ///< input points and crossing vertices
  /// Counter-clockwise triangles in point indices, the neighbour opposite vertex k (-1 on the
  /// boundary), and the segment the edge opposite vertex k lies on: an input segment's index,
  /// kHullSegment for a convex hull edge taken as a segment, -1 for none.
  HostVector<std::int32_t> triangles, neighbors, segment_of;
  static constexpr std::int32_t kHullSegment = -2;
  /// As cdt2d's: -1 for a vertex, else the earlier point with the same coordinates.
  HostVector<std::int32_t> duplicate_of;
  HostVector<double> attribute;  ///< one per triangle, with regions
  /// Triangles left with an angle below min_angle (indices into triangles) and why.
  HostVector<std::int32_t> small_angles;
  HostVector<std::int8_t> small_angle_reasons;  ///< SmallAngle values
  /// Triangles left larger than their bound (only when max_steiner_points stopped refinement).
  HostVector<std::int32_t> large_triangles;
  /// The subsegments: every edge on a segment once (point index pairs, in the order of the
  /// half-edges 3 t + k of the triangle with the lower index), and the segment each lies on (as
  /// segment_of: an input segment, or kHullSegment).
  HostVector<std::int32_t> subsegments, subsegment_of;
  std::int64_t removed_triangles = 0;
  Refine2dStats stats;
  /// Points (2 values each in `points`) and triangles (3 values each in the triangle arrays).
  std::int64_t num_points = 0, num_triangles = 0;
};

/// xy: n points; segments: nseg pairs of point indices. Throws Error(InvalidArgument) for a bound
/// out of range, and as cdt2d throws for the input.
RefinedMesh2d refine2d(const double* xy, std::int64_t n, const std::int32_t* segments,
                       std::int64_t nseg, const Refine2dOptions& opt = {});

/// The result of refine2d_device: arrays in device memory (host memory on the CPU executor).
struct DeviceRefinedMesh2d {
  std::int64_t num_points = 0, num_input_points = 0, num_triangles = 0;
  std::shared_ptr<double> points;                                  ///< 2 * num_points
  std::shared_ptr<std::int32_t> triangles, neighbors, segment_of;  ///< 3 * num_triangles each
  std::shared_ptr<std::int32_t> duplicate_of;                      ///< num_points
  std::shared_ptr<double> attribute;                               ///< with regions
  std::int64_t num_subsegments = 0;
  std::shared_ptr<std::int32_t> subsegments, subsegment_of;  ///< 2 and 1 per subsegment
  /// (host memory) as RefinedMesh2d's.
  std::vector<std::int32_t> small_angles, large_triangles;
  std::vector<std::int8_t> small_angle_reasons;
  std::int64_t removed_triangles = 0;
  Backend backend = Backend::Cuda;
  Refine2dStats stats;
};
/// The device entry: points and segments in the memory of the executor opt picks, the result left
/// there (arrays the caller then owns). Refuses Crossings::Split and max_area_at
/// (Error(InvalidArgument)): both run on the host, so call refine2d.
DeviceRefinedMesh2d refine2d_device(const double* device_xy, std::int64_t n,
                                    const std::int32_t* device_segments, std::int64_t nseg,
                                    const Refine2dOptions& opt = {});

}  // namespace gpugeom
