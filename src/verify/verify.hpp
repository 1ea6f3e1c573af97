// Independent checkers: they use only the exact predicates and plain data structures, never
// any algorithm of the library, so they can judge every output in the tests and in
// `gpugeom check`. Each returns a Report; ok == false comes with a message naming the first
// violation found (which simplex, which vertex, what is wrong).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace gpugeom::verify {

struct Report {
  bool ok = true;
  std::string message;             // first violation, empty when ok
  std::vector<std::string> notes;  // what was checked, and anything checked only partially
  bool fail(const std::string& m) {
    if (ok) message = m;
    ok = false;
    return false;
  }
};

// pts: n points (2 or 3 doubles each). cells: simplices, 3 (2D) or 4 (3D) indices each.
// dup_of (optional, n entries): -1 for a kept point, else the index of the kept point with the
// same coordinates; a duplicate must not be a vertex, every other point must be.
Report check_triangulation2d(const double* pts, std::int64_t n, const std::int32_t* tris,
                             std::int64_t ntri, const std::int32_t* dup_of = nullptr);
Report check_delaunay2d(const double* pts, std::int64_t n, const std::int32_t* tris,
                        std::int64_t ntri, const std::int32_t* dup_of = nullptr);
// The constrained Delaunay triangulation of the convex hull: a valid triangulation in which
// every segment (segs: nseg pairs of point indices) is a chain of edges (a segment through other
// vertices runs along the edges between them), and every interior edge on no segment is
// locally Delaunay (exact in-circle).
Report check_constrained_delaunay2d(const double* pts, std::int64_t n, const std::int32_t* tris,
                                    std::int64_t ntri, const std::int32_t* segs, std::int64_t nseg,
                                    const std::int32_t* dup_of = nullptr);
// A quality mesh of a domain (refine2d): ntri counter-clockwise triangles whose directed edges
// occur once each; seg_of (3 per triangle, the edge opposite vertex k) marks edges on a segment
// (its index, or any value below -1 for a boundary edge that is no input segment; -1: none) and
// must agree on both sides; every boundary edge is marked; every other edge is locally Delaunay
// (exact in-circle); each input segment (segs: nseg pairs) that has marked edges is one path of
// them from its first end to its last, through vertices within 1e-9 of its length's scale of its
// line; every triangle but the exempt ones has its smallest angle >= min_angle (degrees, to
// 1e-9) and its area <= max_area (when > 0).
Report check_refined_mesh2d(const double* pts, std::int64_t n, const std::int32_t* tris,
                            std::int64_t ntri, const std::int32_t* seg_of, const std::int32_t* segs,
                            std::int64_t nseg, const std::int32_t* dup_of, double min_angle,
                            double max_area, const std::int32_t* exempt, std::int64_t nexempt);
Report check_triangulation3d(const double* pts, std::int64_t n, const std::int32_t* tets,
                             std::int64_t ntet, const std::int32_t* dup_of = nullptr);
Report check_delaunay3d(const double* pts, std::int64_t n, const std::int32_t* tets,
                        std::int64_t ntet, const std::int32_t* dup_of = nullptr);

// Convex hull surface: triangles counter-clockwise seen from outside. Checks a closed oriented
// 2-manifold of genus 0, every edge convex, every input point inside or on (all n points when
// n * faces <= max_pairs, else an evenly spaced sample, said in the notes), every vertex extreme.
Report check_hull3d(const double* pts, std::int64_t n, const std::int32_t* tris, std::int64_t ntri,
                    std::int64_t max_pairs = 4'000'000'000LL);

// Triangles as a canonical sorted list (each turned to start at its least index), to compare
// triangulations or hulls whose triangle order differs (the methods and executors may).
std::vector<std::array<std::int32_t, 3>> canonical_triangles(const std::int32_t* tris,
                                                             std::int64_t nt);

// Exact EDT by brute force: shape (rows, cols) or (slices, rows, cols); sites as integer
// coordinates in the same order; sqdist[i] is the claimed squared distance of voxel i to its
// nearest site; nearest (optional) the claimed site index of voxel i, which must be at that
// distance.
Report check_edt(const std::vector<std::int64_t>& shape, const std::vector<std::int64_t>& sites,
                 const std::int64_t* sqdist, const std::int32_t* nearest = nullptr);

}  // namespace gpugeom::verify
