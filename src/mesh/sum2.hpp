// A sum of products in about twice the working precision (internal; the Voronoi diagrams'
// circumcentres): each product split exactly into its rounded value and its error (two_product),
// the values summed with their rounding errors (two_sum), the errors gathered apart and added at
// the end (Ogita, Rump and Oishi's Dot2). A determinant of nearly dependent vectors, which the
// plain formula rounds to 0 (then inf or NaN), keeps its leading digits. The same operations in
// the same order on both executors, so the same bits.
#pragma once
#include "base/hd.hpp"
#include "predicates/expansion.hpp"

namespace gpugeom::mesh {

struct Sum2 {
  double hi = 0, lo = 0;
  GG_HD void add(double v) {
    double s, e;
    exact::two_sum(hi, v, s, e);
    hi = s;
    lo = exact::add_rn(lo, e);
  }
  GG_HD void add_product(double a, double b) {  // += a b
    double p, e;
    exact::two_product(a, b, p, e);
    add(p);
    lo = exact::add_rn(lo, e);
  }
  GG_HD void add_product(double a, double b, double c) {  // += a b c
    double p, e;
    exact::two_product(a, b, p, e);
    add_product(p, c);
    lo = exact::add_rn(lo, exact::mul_rn(e, c));
  }
  GG_HD double value() const { return exact::add_rn(hi, lo); }
};

}  // namespace gpugeom::mesh
