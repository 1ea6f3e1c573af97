// A 2D triangulation on the host that takes constraints (internal to cdt2d): segments are made
// chains of edges by flipping the edges they cross (Sloan, "A fast algorithm for generating
// constrained Delaunay triangulations", 1993), then the edges touched are flipped until every
// edge on no segment is locally Delaunay (Lawson's flips with the segments' edges fixed). Every
// decision is an exact predicate on the input coordinates.
#pragma once
#include <cstdint>
#include <vector>

namespace gpugeom::cdt {

class CdtMesh {
 public:
  // xy: the points; tris / nbrs: a triangulation of their convex hull, counter-clockwise, the
  // triangle opposite vertex k of triangle i at nbrs[3*i + k] (-1 on the hull).
  CdtMesh(const double* xy, std::int64_t n, std::vector<std::int32_t> tris,
          std::vector<std::int32_t> nbrs);

  // Makes segment `id` from point a to point b (a != b, distinct coordinates) a chain of edges
  // and marks them with id (edges already marked keep their mark). Returns false if no flip was
  // needed. Throws Error(InvalidInput) naming `id` and the other segment when an edge of that
  // segment crosses it.
  bool insert_segment(std::int32_t a, std::int32_t b, std::int32_t id);
  // Flips edges on no segment, starting from those of the quadrilaterals the insertions
  // flipped (the triangulation given must be Delaunay), until every one is locally Delaunay.
  void restore_delaunay();

  const std::vector<std::int32_t>& triangles() const { return tri_; }
  const std::vector<std::int32_t>& neighbors() const { return nbr_; }
  const std::vector<std::int32_t>& segment_of() const { return seg_; }
  std::int64_t recovery_flips() const { return recovery_flips_; }
  std::int64_t delaunay_flips() const { return delaunay_flips_; }
  std::int64_t pieces() const { return pieces_; }

 private:
  struct Edge {  // the edge opposite vertex k of triangle t
    std::int32_t t, k;
  };
  const double* p(std::int32_t v) const { return xy_ + 2 * std::int64_t(v); }
  int orient(std::int32_t a, std::int32_t b, std::int32_t c) const;
  // Is w on the line through a and b strictly past u (towards b) and not past b? (u, w on it.)
  bool ahead(std::int32_t a, std::int32_t b, std::int32_t u, std::int32_t w) const;
  // The edge (u, v) as seen from the triangle holding u then v counter-clockwise; t = -1 when
  // no triangle does (a hull edge seen from outside, or no such edge).
  Edge find_edge(std::int32_t u, std::int32_t v) const;
  void mark(std::int32_t u, std::int32_t v, std::int32_t id);
  // Flips the edge e (its quadrilateral must be strictly convex); returns the new edge.
  Edge flip(Edge e);
  // The piece of segment (a, b) from its vertex u: either an edge to a vertex on it (returned
  // with crossed empty), or the edges it crosses up to the next vertex on it (returned).
  std::int32_t walk(std::int32_t a, std::int32_t b, std::int32_t u, std::int32_t id,
                    std::vector<std::pair<std::int32_t, std::int32_t>>& crossed);

  const double* xy_;
  std::int64_t n_;
  std::vector<std::int32_t> tri_, nbr_, seg_;
  std::vector<std::int32_t> vt_;                                // a triangle of each vertex
  std::vector<std::pair<std::int32_t, std::int32_t>> touched_;  // for restore_delaunay
  std::vector<double> scratch_;
  std::int64_t recovery_flips_ = 0, delaunay_flips_ = 0, pieces_ = 0;
};

}  // namespace gpugeom::cdt
