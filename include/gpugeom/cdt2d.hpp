/// @file
/// Exact 2D constrained Delaunay triangulation of points and segments (issue 21).
///
/// The triangulation starts from the exact Delaunay triangulation (delaunay2d.hpp), on the
/// executor opt picks, where the segments are then recovered in parallel rounds: each missing
/// piece of a segment (up to the next input point on it) removes the triangles it crosses, and
/// the two polygons left on its sides are triangulated again by the empty-circle rule (exact
/// in-circle); pieces whose cavities share no triangle, nor a triangle beside one, are rebuilt in
/// the same round. The result is the constrained Delaunay triangulation of the convex hull: every
/// segment is a union of edges, and every other edge is locally Delaunay (cocircular points
/// allowed either way). A segment through other input points is the chain of edges between them.
/// The result is the same on every executor and thread count.
///
/// Holes and the domain's outside are removed as Triangle does for a .poly file: the triangles
/// reachable from a hole's point without crossing a segment go, and with Domain::Enclosed also
/// those reachable from outside the convex hull; region points carry an attribute to the
/// triangles they reach.
///
/// Segments that cross each other at a point inside both are refused, naming both, or split at
/// their intersection (Cdt2dOptions::crossings): a new vertex at the intersection rounded to
/// doubles, reported with the two segments that made it.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

/// A region point: every triangle reachable from its triangle without crossing a segment gets the
/// attribute (Triangle's regional attributes; where regions are not separated by segments the
/// first one given wins). A point on an edge takes one of the triangles beside it.
struct Cdt2dRegion {
  double x = 0, y = 0;
  double attribute = 0;
  /// The region's largest triangle area for refine2d (refine2d.hpp; <= 0: none); cdt2d ignores it.
  double max_area = 0;
};

/// Arrays the caller provides for the results (OutBuffer, common.hpp; as Triangulation2dBuffers):
/// host memory for cdt2d, device memory for cdt2d_device (host memory where it runs on the CPU
/// executor). triangles, neighbors and segment_of must hold at least 3 times the triangle count,
/// which depends on the result (3 * delaunay2d_max_triangles(n) always suffices), attribute (with
/// regions) at least the count, duplicate_of at least n. They are checked once the count is known
/// and before anything is written (Error(InvalidArgument) naming the array and both lengths). An
/// output written into a caller's array is empty (null) in the result; num_triangles says how
/// much of it was written. Crossings::Split refuses them (Error(InvalidArgument)): the new points
/// it adds are known only after the run, and so is the length of duplicate_of.
struct Cdt2dBuffers {
  OutBuffer<std::int32_t> triangles, neighbors, segment_of, duplicate_of;
  OutBuffer<double> attribute;
};

/// The domain of a constrained triangulation, shared by cdt2d (Cdt2dOptions) and refine2d
/// (Refine2dOptions): which triangles are kept, holes, regions and what to do where segments
/// cross.
struct Cdt2dDomainOptions : RunOptions {
  /// Which triangles are kept: the whole hull, or only those enclosed by segments.
  enum class Domain {
    ConvexHull,  ///< every triangle of the convex hull (less the holes)
    Enclosed,    ///< Triangle's -p: the triangles outside the segments are removed too
  };
  Domain domain = Domain::ConvexHull;
  /// What happens where input segments cross: refused, or split at a new vertex.
  enum class Crossings {
    Refuse,  ///< Error(InvalidInput) naming two segments that cross
    Split,   ///< a new vertex where they cross; each segment the chain through its new vertices
  };
  Crossings crossings = Crossings::Refuse;
  /// Hole points (x, y): the triangle holding each and all reachable from it without crossing a
  /// segment are removed. A point outside the convex hull removes nothing.
  std::vector<Point2> holes;
  std::vector<Cdt2dRegion> regions;
};

/// How cdt2d and cdt2d_device run: the domain (Cdt2dDomainOptions) and the caller's output arrays.
struct Cdt2dOptions : Cdt2dDomainOptions {
  Cdt2dBuffers into;  ///< optional
};

/// Statistics of a constrained Delaunay triangulation: the Delaunay triangulation's
/// (Delaunay2dStats: its phases and counters) and the constraints' (phases "delaunay",
/// "segments", "to_host", "domain" with holes, regions or Enclosed, "crossings" first where
/// segments were split). Segment counts are of the pieces where segments were split.
struct Cdt2dStats : Delaunay2dStats {
  /// Segments, those that were chains of Delaunay edges already, and those recovered by
  /// rebuilding cavities.
  std::int64_t segments = 0, segments_present = 0, segments_recovered = 0;
  /// Edges on segments.
  std::int64_t segment_pieces = 0;
  /// Triangles rebuilt in cavities, and edges off a segment with both triangles in its cavity.
  std::int64_t cavity_triangles = 0, cavity_antennas = 0;
  /// Recovery rounds.
  std::int64_t recovery_rounds = 0;
  /// Crossings::Split: the new vertices, and the input segments cut at them.
  std::int64_t crossings = 0, segments_split = 0;

  std::map<std::string, std::int64_t> counter_map() const override;
};

/// The result of cdt2d: triangles, neighbours and the segment each edge lies on, in host memory.
struct ConstrainedTriangulation2d {
  /// Counter-clockwise triangles, 3 input-point indices each, and the triangle opposite vertex k
  /// of triangle i (-1 on the hull), as Triangulation2d's.
  HostVector<std::int32_t> triangles;
  HostVector<std::int32_t> neighbors;
  /// segment_of[3*i + k]: the input segment the edge opposite vertex k of triangle i lies on
  /// (the first one, where several given segments overlap it), -1 for an edge on none.
  HostVector<std::int32_t> segment_of;
  /// One entry per point (the input points, then the new ones): -1 when the point is a vertex,
  /// else the index of the earlier point with the same coordinates, which is the one used
  /// (segments' ends included).
  HostVector<std::int32_t> duplicate_of;
  /// Crossings::Split: the vertices added where segments cross, x and y (point indices n, n+1,
  /// ... in triangles), and for each the two input segments that cross there (where more than
  /// two meet at one point, two of them). An intersection exactly at an input point adds none.
  HostVector<double> new_points;
  HostVector<std::int32_t> new_point_segments;
  std::int64_t num_duplicates = 0;
  /// Segments given with both ends at one point (or at duplicates of it), and segments that
  /// repeat an earlier one (either direction): dropped, counted here.
  std::int64_t zero_length_segments = 0, repeated_segments = 0;
  /// One per triangle when regions are given: the attribute of the region that reached it (0
  /// where none did).
  HostVector<double> attribute;
  /// Triangles removed as holes or outside the domain (they are not in the arrays above, whose
  /// neighbours across a removed triangle are -1).
  std::int64_t removed_triangles = 0;
  Cdt2dStats stats;
  /// Triangles (each array above holds 3 per triangle).
  std::int64_t num_triangles = 0;
};

/// xy: n points, x and y interleaved; segments: nseg pairs of point indices. Throws
/// Error(InvalidInput) for a segment naming a point outside 0..n-1, and (Crossings::Refuse) for
/// two segments that cross each other at a point inside both, naming both (segments that meet at
/// an input point, or overlap along one line, are fine); and as delaunay2d does for the points.
ConstrainedTriangulation2d cdt2d(const double* xy, std::int64_t n, const std::int32_t* segments,
                                 std::int64_t nseg, const Cdt2dOptions& opt = {});

/// The result of cdt2d_device: arrays in device memory (host memory on the CPU executor). An
/// array written into the caller's (Cdt2dOptions::into) is null here.
struct DeviceConstrainedTriangulation2d {
  std::int64_t num_points = 0, num_triangles = 0, num_duplicates = 0;
  std::shared_ptr<std::int32_t> triangles, neighbors, segment_of;  ///< 3 * num_triangles each
  std::shared_ptr<std::int32_t> duplicate_of;                      ///< num_points
  std::shared_ptr<double> attribute;  ///< num_triangles, when regions are given
  std::int64_t zero_length_segments = 0, repeated_segments = 0, removed_triangles = 0;
  Backend backend = Backend::Cuda;  ///< where the arrays are: Cuda = device memory
  Cdt2dStats stats;
};
/// The device entry: points (n, x and y interleaved) and segments (nseg index pairs) in the
/// memory of the executor opt picks (CUDA device memory, or host memory for Backend::Cpu), the
/// result left there (arrays the caller then owns; freed with the last copy of the pointer).
/// The same triangles, marks and counts as cdt2d. Crossings::Split is refused here
/// (Error(InvalidArgument)): splitting reads the segments on the host, so call cdt2d.
DeviceConstrainedTriangulation2d cdt2d_device(const double* device_xy, std::int64_t n,
                                              const std::int32_t* device_segments,
                                              std::int64_t nseg, const Cdt2dOptions& opt = {});

}  // namespace gpugeom
