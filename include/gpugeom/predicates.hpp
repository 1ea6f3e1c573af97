/// @file
/// Exact geometric predicates for host code (see src/predicates/predicates.hpp for the
/// conventions; device code includes that header directly). Results are -1, 0 or +1; the
/// *_sos variants break every tie by simulation of simplicity, are consistent under any
/// permutation of their arguments, and never return 0 for distinct points (or distinct indices).
/// The perturbation depends on the points' coordinates alone (the index orders only equal
/// points): lifts in decreasing lexicographic order, as CGAL's Delaunay perturbation, and
/// coordinates in Z order of their bits (src/predicates/sos.hpp).
#pragma once
#include "gpugeom/common.hpp"

namespace gpugeom {

/// Sign of the orientation of a, b, c: +1 counter-clockwise, -1 clockwise, 0 collinear (exact).
int orient2d(const Point2& a, const Point2& b, const Point2& c);
/// Sign of det[b-a; c-a; d-a] (exact): the side of plane abc that d is on.
int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d);
/// +1 where d lies inside the circle through a, b, c (counter-clockwise), -1 outside, 0 on it
/// (exact).
int incircle(const Point2& a, const Point2& b, const Point2& c, const Point2& d);
/// +1 where e lies inside the sphere through a, b, c, d (abcd positively oriented), -1 outside, 0
/// on it (exact).
int insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d, const Point3& e);
/// Orientation of five 4D points (x, y, z, w): det[b-a; c-a; d-a; e-a].
int orient4d(const double a[4], const double b[4], const double c[4], const double d[4],
             const double e[4]);
/// orient4d of 3D points lifted to the paraboloid; equals -insphere.
int orient4d_lifted(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                    const Point3& e);

/// orient2d with ties broken by simulation of simplicity: never 0 for distinct points; ia, ib, ic
/// order equal points.
int orient2d_sos(const Point2& a, int ia, const Point2& b, int ib, const Point2& c, int ic);
/// orient3d with ties broken by simulation of simplicity: never 0 for distinct points.
int orient3d_sos(const Point3& a, int ia, const Point3& b, int ib, const Point3& c, int ic,
                 const Point3& d, int id);
/// incircle with ties broken by simulation of simplicity: never 0 for distinct points.
int incircle_sos(const Point2& a, int ia, const Point2& b, int ib, const Point2& c, int ic,
                 const Point2& d, int id);
/// insphere with ties broken by simulation of simplicity: never 0 for distinct points.
int insphere_sos(const Point3& a, int ia, const Point3& b, int ib, const Point3& c, int ic,
                 const Point3& d, int id, const Point3& e, int ie);
/// orient4d with ties broken by simulation of simplicity.
int orient4d_sos(const double a[4], int ia, const double b[4], int ib, const double c[4], int ic,
                 const double d[4], int id, const double e[4], int ie);
/// orient4d_lifted with ties broken by simulation of simplicity (the same perturbation as
/// insphere_sos).
int orient4d_lifted_sos(const Point3& a, int ia, const Point3& b, int ib, const Point3& c, int ic,
                        const Point3& d, int id, const Point3& e, int ie);

/// True when every coordinate is 0 or has a magnitude in [2^-142, 2^180], the range in which
/// the predicates are exact.
bool in_exact_range(double v);

}  // namespace gpugeom
