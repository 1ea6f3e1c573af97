// Host entry points of the predicates: each call brings thread-local scratch.
#include "gpugeom/predicates.hpp"

#include <vector>

#include "predicates/predicates.hpp"

namespace gpugeom {
namespace {
double* scratch() {
  constexpr int n =
      exact::cmax(exact::cmax(pred::kOrient2dScratch, pred::kOrient3dScratch),
                  exact::cmax(pred::kIncircleScratch,
                              exact::cmax(pred::kInsphereScratch, pred::kOrient4dScratch)));
  thread_local std::vector<double> s(n);
  return s.data();
}
const double* p(const Point2& q) {
  return &q.x;
}
const double* p(const Point3& q) {
  return &q.x;
}
}  // namespace

static_assert(sizeof(Point2) == 2 * sizeof(double) && sizeof(Point3) == 3 * sizeof(double),
              "points must be packed doubles");

int orient2d(const Point2& a, const Point2& b, const Point2& c) {
  return pred::orient2d(p(a), p(b), p(c), scratch());
}
int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return pred::orient3d(p(a), p(b), p(c), p(d), scratch());
}
int incircle(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
  return pred::incircle(p(a), p(b), p(c), p(d), scratch());
}
int insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d, const Point3& e) {
  return pred::insphere(p(a), p(b), p(c), p(d), p(e), scratch());
}
int orient4d(const double a[4], const double b[4], const double c[4], const double d[4],
             const double e[4]) {
  return pred::orient4d(a, b, c, d, e, scratch());
}
int orient4d_lifted(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                    const Point3& e) {
  return pred::orient4d_lifted(p(a), p(b), p(c), p(d), p(e), scratch());
}
int orient2d_sos(const Point2& a, int ia, const Point2& b, int ib, const Point2& c, int ic) {
  return pred::orient2d_sos(p(a), ia, p(b), ib, p(c), ic, scratch());
}
int orient3d_sos(const Point3& a, int ia, const Point3& b, int ib, const Point3& c, int ic,
                 const Point3& d, int id) {
  return pred::orient3d_sos(p(a), ia, p(b), ib, p(c), ic, p(d), id, scratch());
}
int incircle_sos(const Point2& a, int ia, const Point2& b, int ib, const Point2& c, int ic,
                 const Point2& d, int id) {
  return pred::incircle_sos(p(a), ia, p(b), ib, p(c), ic, p(d), id, scratch());
}
int insphere_sos(const Point3& a, int ia, const Point3& b, int ib, const Point3& c, int ic,
                 const Point3& d, int id, const Point3& e, int ie) {
  return pred::insphere_sos(p(a), ia, p(b), ib, p(c), ic, p(d), id, p(e), ie, scratch());
}
int orient4d_sos(const double a[4], int ia, const double b[4], int ib, const double c[4], int ic,
                 const double d[4], int id, const double e[4], int ie) {
  return pred::orient4d_sos(a, ia, b, ib, c, ic, d, id, e, ie, scratch());
}
int orient4d_lifted_sos(const Point3& a, int ia, const Point3& b, int ib, const Point3& c, int ic,
                        const Point3& d, int id, const Point3& e, int ie) {
  return pred::orient4d_lifted_sos(p(a), ia, p(b), ib, p(c), ic, p(d), id, p(e), ie, scratch());
}
bool in_exact_range(double v) {
  return pred::in_exact_range(v);
}

}  // namespace gpugeom
