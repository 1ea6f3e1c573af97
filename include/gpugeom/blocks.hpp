/// @file
/// Block-level pieces of the distributed Delaunay triangulation (issue 51): what one block of
/// `gpugeom.dask.delaunay` runs over all its simplices, in C++ so that the per-simplex arithmetic
/// does not cost NumPy temporaries (docs/design-notes.md, "Distributed Delaunay on Dask").
#pragma once
#include <cstdint>

#include "gpugeom/host_vector.hpp"

namespace gpugeom {

/// The boxes of a block's finality test, in the first `dim` entries (2 or 3): `region` is the
/// closed box whose points the block holds, `bounds` the closed box of all points, and `scale`
/// the largest coordinate magnitude of `bounds` (the rounding of a centre is bounded relative
/// to it).
struct BlockBoxes {
  double region_lo[3] = {}, region_hi[3] = {};
  double bounds_lo[3] = {}, bounds_hi[3] = {};
  double scale = 0.0;
};

/// For `count` simplices of `points` (row-major, `dim` coordinates a point): simplex i has the
/// `dim` + 1 vertex indices `simplices[(rows ? rows[i] : i) * (dim + 1) + k]`. Writes
/// inside[i] = 1 where the simplex's closed circumball, grown by a bound of the rounding of its
/// centre and radius, misses every part of `bounds` beyond `region`: no point outside the
/// region can lie in it. Writes 0 where it may reach such a point or its centre is not trusted
/// (a singular simplex, or one whose condition number exceeds 1e10). Conservative: a 0 is not
/// a verdict, the caller tests those simplices further. Runs on `threads` host threads (0:
/// OpenMP's default). Throws Error(InvalidArgument) for a dim other than 2 or 3.
void circumballs_inside_region(const double* points, int dim, const std::int64_t* simplices,
                               const std::int64_t* rows, std::int64_t count,
                               const BlockBoxes& boxes, std::uint8_t* inside, int threads = 0);
/// The same, for int32 vertex indices (as a triangulation gives them).
void circumballs_inside_region(const double* points, int dim, const std::int32_t* simplices,
                               const std::int64_t* rows, std::int64_t count,
                               const BlockBoxes& boxes, std::uint8_t* inside, int threads = 0);

/// What a block requires of its local triangulation (`m` simplices of `dim` + 1 local vertex
/// indices each, and their neighbours: `neighbors[i * (dim + 1) + j]` is the simplex across the
/// face opposite vertex j, -1 on the hull). Local indices follow the global order, so a
/// simplex's lowest local vertex is its lowest global one, and it is *owned* by the block where
/// that vertex is one of the block's own points (`owned[v]` nonzero).
struct BlockRequired {
  /// The owned simplices, in increasing order.
  HostVector<std::int64_t> owned_rows;
  /// Per simplex, 1 where it must be final: it has an own vertex (the stars of the own points;
  /// the neighbours across blocks are matched by their faces, block_output).
  HostVector<std::uint8_t> required;
};
/// What a block requires of its local triangulation (BlockRequired), on `threads` host threads
/// (0: OpenMP's default). Throws Error(InvalidArgument) for a dim other than 2 or 3.
BlockRequired block_required(const std::int64_t* simplices, const std::int64_t* neighbors,
                             std::int64_t m, int dim, const std::uint8_t* owned, int threads = 0);
/// The same, for int32 indices (as a triangulation gives them: half the bytes to copy from a
/// GPU).
BlockRequired block_required(const std::int32_t* simplices, const std::int32_t* neighbors,
                             std::int64_t m, int dim, const std::uint8_t* owned, int threads = 0);

/// A block's output: its owned simplices `rows` (all of them, as block_required lists them)
/// in global point ids (`ids`: per local point), and per face the neighbour as an index into
/// `rows` or -1 (none) or -2 (not owned here). A neighbour with an own vertex is final, so
/// across a -1 or a row the neighbour is the global one; across a -2 it is owned by another
/// block, which may not be the local neighbour's owner (a neighbour without an own vertex may
/// not be final), so each -2 face is a request by the face itself, in row-major order: the block
/// that matches it (`blk[v]` of the face's lowest vertex v), the face's `dim` global vertex ids
/// sorted, and its position row * (dim + 1) + face (match_faces pairs the two simplices of
/// each such face). A face on the local hull is on the global hull where it has an own vertex
/// (-1); without one it is an *open* request (`request_open`), which the matcher answers with
/// -1 where no other simplex has the face. `vertices`: the local points the rows use, in
/// increasing order.
///
/// Every index is 32-bit, as a single triangulation's (gpugeom.dask takes fewer than 2^31 - 1
/// points; a block's rows are local): half the bytes of the 64-bit output that a distributed
/// result keeps per block, moves between workers and gathers.
struct BlockOutput {
  HostVector<std::int32_t> simplices, neighbors;
  HostVector<std::int32_t> request_owner, request_key, request_pos;
  HostVector<std::uint8_t> request_open;
  HostVector<std::int32_t> vertices;
  /// The vertices' global ids, and (where the points were given) their coordinates, `dim` a
  /// vertex.
  HostVector<std::int32_t> vertex_ids;
  HostVector<double> vertex_points;
};
/// The output of a block's owned simplices `rows` (BlockOutput), on `threads` host threads (0:
/// OpenMP's default); `ids` and `blk` per local point (its global id and its block), `points`
/// (the `n` local points, or null) for the vertices' coordinates. Throws Error(InvalidArgument)
/// for a dim other than 2 or 3, Error(Unsupported) where the rows' faces pass 2^31 - 1 (a block
/// too large for 32-bit positions: more blocks).
BlockOutput block_output(const std::int64_t* simplices, const std::int64_t* neighbors,
                         std::int64_t m, int dim, const std::int64_t* rows, std::int64_t count,
                         const std::int32_t* ids, const std::int32_t* blk, const double* points,
                         std::int64_t n, int threads = 0);
/// The same, for int32 simplices and neighbours.
BlockOutput block_output(const std::int32_t* simplices, const std::int32_t* neighbors,
                         std::int64_t m, int dim, const std::int64_t* rows, std::int64_t count,
                         const std::int32_t* ids, const std::int32_t* blk, const double* points,
                         std::int64_t n, int threads = 0);

/// Pairs the `q` face requests that come to one block from every block (BlockOutput's, `keys`
/// their `dim` sorted vertex ids each, `positions` their global positions simplex * (dim + 1) +
/// face): each face is a face of exactly two owned simplices, so each key comes exactly twice,
/// but for an open request (`open[i]` nonzero, or null for none) of a face on the hull, which
/// comes once. Returns per request its partner's position, -1 for an open one alone. Throws
/// Error(Internal) where a key comes otherwise (a bug), Error(InvalidArgument) for a dim other
/// than 2 or 3.
HostVector<std::int64_t> match_faces(const std::int64_t* keys, const std::int64_t* positions,
                                     const std::uint8_t* open, std::int64_t q, int dim,
                                     int threads = 0);
/// The same, for int32 keys (BlockOutput's).
HostVector<std::int64_t> match_faces(const std::int32_t* keys, const std::int64_t* positions,
                                     const std::uint8_t* open, std::int64_t q, int dim,
                                     int threads = 0);

/// The neighbours of a block's `m` output simplices in global simplex indices: `neighbors` is
/// BlockOutput's (an index into the block's own rows, -1 none, -2 another block's) and `offset`
/// the block's first global index; the `q` answers to its requests are its positions `pos`
/// (row * (dim + 1) + face) and the global index of the simplex across each (-1: none, an open
/// face on the hull). Row-major, (dim + 1) entries a simplex, -1 on the hull, as `Index`
/// (std::int32_t, as a single triangulation's, where every global index fits; else
/// std::int64_t). On `threads` host threads (0: OpenMP's default). Throws Error(Internal) where
/// a -2 face has no answer, Error(InvalidArgument) for a dim other than 2 or 3, a position out
/// of range, or a global index past `Index`. Defined for those two widths alone (in the
/// library).
template <class Index>
HostVector<Index> block_neighbors(const std::int32_t* neighbors, std::int64_t m, int dim,
                                  std::int64_t offset, const std::int64_t* pos,
                                  const std::int64_t* across, std::int64_t q, int threads = 0);

/// The bounds of a set of points, and its first point with a NaN or infinite coordinate.
struct PointBounds {
  double lo[3] = {}, hi[3] = {};
  /// The lowest index of a point with a coordinate that is not finite, -1 where there is none
  /// (then lo and hi are the bounds; for n = 0 they are +inf and -inf).
  std::int64_t first_bad = -1;
};
/// The bounds of `n` points (`dim` coordinates each, row-major) in one pass on `threads` host
/// threads (0: OpenMP's default): the check of a piece of gpugeom.dask's input, where NumPy's
/// reductions along the short axis and its finiteness test cost 17 ms for 2.5·10^5 points.
/// Throws Error(InvalidArgument) for a dim other than 2 or 3.
PointBounds point_bounds(const double* points, int dim, std::int64_t n, int threads = 0);

/// A grid of cells over the box from `lo` (`dim` coordinates), `counts[j]` cells of width
/// `width[j]` along axis j. A point's cell is floor((x_j - lo_j) / width_j) per axis, clamped to
/// the grid (0 where the width is 0), row-major over the axes.
struct CellGrid {
  double lo[3] = {}, width[3] = {};
  std::int64_t counts[3] = {1, 1, 1};
};

/// The points' cells (`cell`, per point) and the points of each block (`order`, with `cuts`:
/// block b's points are order[cuts[b]:cuts[b + 1]], in increasing order). Block b is the cell of
/// that index; its points are those of its cell and, with split_to_blocks, those in its boxes.
struct CellSplit {
  HostVector<std::int64_t> cell, order, cuts;
  /// After gather_blocks: the points (`dim` coordinates each) and their cells, in `order`.
  HostVector<double> points;
  HostVector<std::int64_t> cells;
};
/// Splits `n` points (`dim` coordinates each) by the cells of `grid`, on `threads` host threads
/// (0: OpenMP's default): each point is in its cell's block only. Throws Error(InvalidArgument)
/// for a dim other than 2 or 3.
CellSplit split_by_cell(const double* points, int dim, std::int64_t n, const CellGrid& grid,
                        int threads = 0);
/// The bins beside empty space each block takes in its first round besides its region
/// (empty_frontiers): block b's are bins[offsets[b]:offsets[b + 1]] of `grid` (increasing),
/// holding points[b] points in all.
struct BlockFrontiers {
  CellGrid grid;
  HostVector<std::int64_t> offsets, bins, points;
};
/// For bins (`bins`, row-major, `counts` points each) and `nblocks` blocks' regions (closed
/// boxes `region_lo`/`region_hi`, `dim` coordinates a block): per block the occupied bins next
/// to (sharing a side, an edge or a corner with) an empty bin that its region reaches through
/// empty bins, leaving out the bins strictly inside its region. Where the points leave empty
/// space (between clusters, round a ball), the Delaunay balls of the points near it span that
/// space and end on the points across it, which a ghost layer does not hold; gpugeom.dask's
/// first round holds these bins' points too, so that its test passes. A block whose bins would
/// hold more than `cap` points keeps only those within `band` of its region (points in a ball:
/// its surface all round is beside one empty space), and past the cap still gets none (points
/// on a sphere: every bin is beside empty space). Deterministic; on `threads` host threads (0:
/// OpenMP's default). Throws Error(InvalidArgument) for a dim other than 2 or 3.
BlockFrontiers empty_frontiers(const std::int32_t* counts, const CellGrid& bins, int dim,
                               const double* region_lo, const double* region_hi,
                               std::int64_t nblocks, std::int64_t cap, double band = 0,
                               int threads = 0);

/// Splits `n` points to the blocks of `grid` (CellSplit): a point goes to its cell's block, to
/// the block `box_block[i]` of every one of the `nboxes` closed boxes i holding it
/// (`box_lo[i * dim + j] <= x_j <= box_hi[i * dim + j]`, comparisons of the doubles only), and,
/// where `frontiers` is given, to every block listing its bin of `frontiers->grid`; once per
/// block. The boxes come by block (box_block not decreasing). Where `wanted` is given, only
/// the blocks b with wanted[b] nonzero get points. Deterministic on any thread count. Throws
/// Error(InvalidArgument) for a dim other than 2 or 3, a box's block outside the grid or out
/// of order, or frontiers for another count of blocks or naming a bin outside their grid.
CellSplit split_to_blocks(const double* points, int dim, std::int64_t n, const CellGrid& grid,
                          const double* box_lo, const double* box_hi, const std::int64_t* box_block,
                          std::int64_t nboxes, const std::uint8_t* wanted = nullptr,
                          int threads = 0, const BlockFrontiers* frontiers = nullptr);

/// Fills `split.points` and `split.cells` (CellSplit) from the points it split, on `threads`
/// host threads (0: OpenMP's default): each block's part then lies in one slice.
void gather_blocks(const double* points, int dim, CellSplit& split, int threads = 0);

/// How many of `n` points (`dim` coordinates each) lie in each cell of `grid` (row-major; a
/// point's cell as CellGrid says), on `threads` host threads (0: OpenMP's default). Throws
/// Error(InvalidArgument) for a dim other than 2 or 3, more than 2^31 - 1 points or more than
/// 2^28 cells.
HostVector<std::int32_t> cell_counts(const double* points, int dim, std::int64_t n,
                                     const CellGrid& grid, int threads = 0);

/// Balls (`m` centres of `dim` coordinates and their reaches), each cut to a closed box (`lo`,
/// `hi`, `dim` coordinates a ball), against the cells of `grid` with `marked[cell]` nonzero (the
/// bins that hold points a block lacks): a cell *meets* a ball where its box, grown by `margin`,
/// meets the cut box and lies within the reach of the centre; a reach that is not finite meets
/// every marked cell of the cut box. The test of the region past a block's cells for
/// gpugeom.dask: a ball that meets no marked cell holds no point the block lacks. Returns per
/// ball 1 where it meets a marked cell (a ball's scan stops at the first), on `threads` host
/// threads (0: OpenMP's default). Throws Error(InvalidArgument) for a dim other than 2 or 3 or
/// more than 2^28 cells.
HostVector<std::uint8_t> balls_in_bins(const double* centres, const double* reach, const double* lo,
                                       const double* hi, std::int64_t m, int dim,
                                       const CellGrid& grid, const std::uint8_t* marked,
                                       double margin, int threads = 0);

/// What a block sends the other blocks of `grid` (block_borders): per target block, in
/// increasing order (`targets`), the local indices of its own points the target needs,
/// increasing: `vertices[offsets[k]:offsets[k + 1]]` for targets[k].
struct BlockBorders {
  HostVector<std::int64_t> targets, offsets, vertices;
};
/// The border of block `block` of `grid` (the cells are the blocks) from its local
/// triangulation (`m` simplices and their neighbours over `n` local points, `owned` marking its
/// own points): every own point that is a vertex of a simplex whose closed circumball (grown by
/// a bound of its rounding) meets another block's cell grown by `margin`, or of a hull face (no
/// neighbour) whose plane meets it; a ball whose centre is not trusted meets every cell. A
/// block's stars are those of the global triangulation when it holds, besides its own points,
/// every other block's border for it (docs/design-notes.md). `scale`: the largest coordinate
/// magnitude of the points' bounds. Where `boxes` is given, also writes per simplex `inside[i]`
/// (`m` bytes): circumballs_inside_region's verdict for the simplices with an own vertex (the
/// same ball, computed once), 0 for the others. Deterministic on any thread count. Throws
/// Error(InvalidArgument) for a dim other than 2 or 3 or a block outside the grid.
BlockBorders block_borders(const double* points, int dim, const std::int64_t* simplices,
                           const std::int64_t* neighbors, std::int64_t m, std::int64_t n,
                           const std::uint8_t* owned, std::int64_t block, const CellGrid& grid,
                           double margin, double scale, const BlockBoxes* boxes = nullptr,
                           std::uint8_t* inside = nullptr, int threads = 0);
/// The same, for int32 simplices and neighbours.
BlockBorders block_borders(const double* points, int dim, const std::int32_t* simplices,
                           const std::int32_t* neighbors, std::int64_t m, std::int64_t n,
                           const std::uint8_t* owned, std::int64_t block, const CellGrid& grid,
                           double margin, double scale, const BlockBoxes* boxes = nullptr,
                           std::uint8_t* inside = nullptr, int threads = 0);

/// Whether a block's stars are final, against every point (the test of the multi-device
/// triangulation, which holds all points in one process; gpugeom.dask's blocks, which see only
/// counts per bin, test in Python). For the `m` simplices of the block's local triangulation
/// (`dim` + 1 local indices each into `points`), true where no simplex i with `test[i]` nonzero
/// has a point of `all` in its closed circumball (grown by a bound of its rounding) that the
/// block lacks: one outside the closed box `boxes.region` and the `nextra` closed boxes
/// `extra_lo`/`extra_hi` (`dim` coordinates each: the strips along the bounds a block also
/// holds) and not among the `nheld` points `held` (global indices, increasing: the block's
/// other local points). False
/// also where a centre is not trusted (a singular or ill-conditioned simplex). `all` is indexed
/// by the cells of `bins` over `boxes.bounds` (split_by_cell's `order` and `cuts`). A simplex
/// whose ball misses the bounds beyond the region passes at once; the others scan the bins
/// their ball meets there; the first failure ends the test. On `threads` host threads (0:
/// OpenMP's default); deterministic. Throws Error(InvalidArgument) for a dim other than 2 or 3.
bool stars_final(const double* points, int dim, const std::int32_t* simplices, std::int64_t m,
                 const std::uint8_t* test, const BlockBoxes& boxes, const double* all,
                 const CellGrid& bins, const std::int64_t* order, const std::int64_t* cuts,
                 const std::int64_t* held, std::int64_t nheld, const double* extra_lo = nullptr,
                 const double* extra_hi = nullptr, std::int64_t nextra = 0, int threads = 0);

/// The points of a 2D set (`n` points, x and y each) that may be extreme points of a larger set
/// holding them: all but those strictly inside the polygon through their extreme points in 8
/// directions. A point is dropped only where every orientation against the polygon's edges is
/// positive beyond its rounding bound (Shewchuk's ccwerrboundA); a point strictly left of every
/// edge of a closed counter-clockwise polygon of input points lies strictly inside their hull,
/// whatever the rounding of the directions chose, so no perturbation makes it extreme. Returns
/// their indices, increasing; every index for fewer than 4 points or a flat polygon. On
/// `threads` host threads (0: OpenMP's default).
HostVector<std::int64_t> hull_candidates2d(const double* points, std::int64_t n, int threads = 0);

}  // namespace gpugeom
