// Points, the kernel point and the decisions of the hull algorithm, written once for the two
// predicate stages of thesis 6.3: included inside gpugeom::hull3d::{cpu,cuda}_impl.
//
// Every decision is a function template over an orientation evaluator O: FastOrient runs the
// floating-point filter and returns 0 when it cannot tell, and the decision then returns
// kUndecided at once; ExactOrient runs the exact stage with simulation of simplicity and
// never returns 0. A kernel runs the fast version for every item and queues the undecided
// ones; a second kernel runs the exact version over that short list with bounded scratch. The
// kernel point s takes part in the predicates as point number n (after every input point), so
// the perturbation is one consistent scheme for every test.

using u64 = std::uint64_t;

using mesh::kUndecided;  // (mesh/decision.hpp)
constexpr int kScratch = pred::kOrient3dScratch;

struct Geo {
  const double* p;  // 3 doubles per point
  const double* s;  // the kernel point, on the executor too (not an array in here: at() would
                    // hand out the address of a member, and every copy of Geo, the team's
                    // included, would live in local memory)
  std::int32_t n;   // its index
  GG_HD const double* at(std::int32_t i) const { return i == n ? s : p + 3 * std::int64_t(i); }
};

struct FastOrient {
  Geo g;
  GG_HD int operator()(std::int32_t i, std::int32_t j, std::int32_t k, std::int32_t l) const {
    return pred::orient3d_fast(g.at(i), g.at(j), g.at(k), g.at(l));
  }
};
// The exact stage is a call, not inlined code: it is rare, and inlined at each of a decision's
// orientation tests it made the team kernel 1 MB of code with registers spilled on the fast
// path too (1 KB of stack per thread).
#if defined(__CUDACC__)
#define GG_HULL_NOINLINE __host__ __device__ __noinline__
#else
#define GG_HULL_NOINLINE __attribute__((noinline))
#endif
struct ExactOrient {
  Geo g;
  double* scratch;
  GG_HULL_NOINLINE int operator()(std::int32_t i, std::int32_t j, std::int32_t k,
                                  std::int32_t l) const {
    return pred::orient3d_sos(g.at(i), i, g.at(j), j, g.at(k), k, g.at(l), l, scratch);
  }
};

#define GG_HULL_SIGN(var, expr) \
  const int var = (expr);       \
  if (var == 0) return kUndecided

// The distance key of point q above facet (a, b, c): the orientation determinant rounded to
// float (proportional to the distance for one facet), then the smaller index on ties. Written
// with the FMA-free helpers so both executors choose the same points.

// A facet's farthest point is the one of largest key: the rounded distance above the facet
// (as a float), then among equal distances a fixed scatter of the index (mesh/priority.hpp). Ties
// are common where points lie in the facet's plane (distance 0: points on a hull edge, inside a
// face); taking the lowest index there would insert the points of a run in index order, one round
// each when the input lists them along the run, while a scrambled choice splits runs like a random
// pivot.
GG_HD inline u64 distance_key(const Geo& g, std::int32_t a, std::int32_t b, std::int32_t c,
                              std::int32_t q) {
  using namespace pred;
  const double *pa = g.at(a), *pb = g.at(b), *pc = g.at(c), *pq = g.at(q);
  double u[3], v[3], w[3];
  for (int d = 0; d < 3; ++d) {
    u[d] = sub_rn(pb[d], pa[d]);
    v[d] = sub_rn(pc[d], pa[d]);
    w[d] = sub_rn(pq[d], pa[d]);
  }
  const double det = add_rn(add_rn(mul_rn(w[0], sub_rn(mul_rn(u[1], v[2]), mul_rn(u[2], v[1]))),
                                   mul_rn(w[1], sub_rn(mul_rn(u[2], v[0]), mul_rn(u[0], v[2])))),
                            mul_rn(w[2], sub_rn(mul_rn(u[0], v[1]), mul_rn(u[1], v[0]))));
  const float f = det > 0 ? float(det) : 0.0f;
  std::uint32_t bits;
  memcpy(&bits, &f, 4);
  // (q + 1: scatter(0) = 0, and a key of 0 means "no point")
  return (u64(bits) << 32) | u64(mesh::scatter(std::uint32_t(q) + 1));
}
GG_INLINE std::int32_t point_of_key(u64 key) {
  return std::int32_t(mesh::unscatter(std::uint32_t(key & 0xFFFFFFFFu)) - 1);
}

// Point q (not a vertex) against the four facets of the first tetrahedron (fv: 4 x 3 vertex
// indices): the facet whose cone from s holds q when q lies outside it, -1 when q lies inside
// the tetrahedron, kLost if no cone holds q (cannot happen: the cones partition space).
constexpr int kLost = -2;
template <class O>
GG_HD int locate_first(const O& o, std::int32_t s, const std::int32_t* fv, std::int32_t q) {
  for (int f = 0; f < 4; ++f) {
    const std::int32_t a = fv[3 * f], b = fv[3 * f + 1], c = fv[3 * f + 2];
    GG_HULL_SIGN(r1, o(s, a, b, q));
    if (r1 < 0) continue;
    GG_HULL_SIGN(r2, o(s, b, c, q));
    if (r2 < 0) continue;
    GG_HULL_SIGN(r3, o(s, c, a, q));
    if (r3 < 0) continue;
    GG_HULL_SIGN(up, o(a, b, c, q));
    return up > 0 ? f : -1;
  }
  return kLost;
}

// Facet (v0, v1, v2) held q in its cone and was split at p into children k = (p, v[k+1],
// v[k+2]). Returns the child whose cone holds q when q lies outside that child, else -1.
// The rays s->v_k cut the cone into three sectors around s->p, each under half a turn, so two
// orientations name the sector.
template <class O>
GG_HD int locate_child(const O& o, std::int32_t s, std::int32_t p, const std::int32_t* v,
                       std::int32_t q) {
  GG_HULL_SIGN(a0, o(s, p, v[0], q));
  int child;
  if (a0 > 0) {
    GG_HULL_SIGN(a1, o(s, p, v[1], q));
    child = a1 < 0 ? 2 : 0;
  } else {
    GG_HULL_SIGN(a2, o(s, p, v[2], q));
    child = a2 > 0 ? 1 : 0;
  }
  GG_HULL_SIGN(up, o(p, v[(child + 1) % 3], v[(child + 2) % 3], q));
  return up > 0 ? child : -1;
}

// Flip-Flop's decision for the edge ab shared by facets (a, b, c) and (b, a, d) (thesis
// Alg. 5.4). deg_*: vertex degrees; ne_*: vertices labelled non-extreme.
enum EdgeAction : int {
  kNone = 0,
  kFlip22 = 1,
  kRemoveA = 2,
  kRemoveB = 3,
  kLabelA = 4,
  kLabelB = 5
};

// Removing x, whose three facets fan out to the triangle (u, v, w), keeps the surface
// star-shaped iff s lies strictly inside (u, v, w)'s plane and x lies in its cone.
template <class O>
GG_HD int removable(const O& o, std::int32_t s, std::int32_t x, std::int32_t u, std::int32_t v,
                    std::int32_t w) {
  GG_HULL_SIGN(in, o(u, v, w, s));
  if (in > 0) return 0;
  GG_HULL_SIGN(c1, o(s, u, v, x));
  if (c1 < 0) return 0;
  GG_HULL_SIGN(c2, o(s, v, w, x));
  if (c2 < 0) return 0;
  GG_HULL_SIGN(c3, o(s, w, u, x));
  return c3 > 0 ? 1 : 0;
}

template <class O>
GG_HD int edge_action(const O& o, std::int32_t s, std::int32_t a, std::int32_t b, std::int32_t c,
                      std::int32_t d, std::int32_t deg_a, std::int32_t deg_b,
                      const std::int8_t* ne) {
  GG_HULL_SIGN(refl, o(a, b, c, d));
  const bool reflex = refl > 0;                // d above (a, b, c): the surface folds inward at ab
  if (deg_a == 3 && deg_b == 3) return kNone;  // a tetrahedron: convex already
  if (deg_a == 3 || deg_b == 3) {
    // A 3-1 flip: removing a leaves (b, c, d); removing b leaves (c, a, d). Case 1: do it
    // when it grows the volume (the edge is reflex) or removes a labelled vertex.
    const bool ra = deg_a == 3;
    const std::int32_t x = ra ? a : b;
    if (!reflex && !ne[x]) return kNone;
    const int ok = ra ? removable(o, s, a, b, c, d) : removable(o, s, b, c, a, d);
    if (ok == kUndecided) return kUndecided;
    return ok ? (ra ? kRemoveA : kRemoveB) : kNone;
  }
  // A 2-2 flip makes (a, d, c) and (b, c, d): their cones cover the old ones iff a and b lie
  // on opposite sides of the plane through s, c, d (and s stays inside both new facets).
  GG_HULL_SIGN(oa, o(s, c, d, a));
  GG_HULL_SIGN(ob, o(s, c, d, b));
  if (!(oa < 0 && ob > 0)) {
    // Unflippable. When reflex, the corner lying in the cone of the other three is inside the
    // tetrahedron (s, and those three): non-extreme (Lemma 5.1).
    if (!reflex) return kNone;
    return oa > 0 ? kLabelA : kLabelB;
  }
  GG_HULL_SIGN(s1, o(a, d, c, s));
  if (s1 > 0) return kNone;
  GG_HULL_SIGN(s2, o(b, c, d, s));
  if (s2 > 0) return kNone;
  // Cases 2 and 3: x = the labelled vertex of smallest index among a, b, c, d.
  std::int32_t x = -1;
  for (std::int32_t y : {a, b, c, d})
    if (ne[y] && (x < 0 || y < x)) x = y;
  if (x < 0) return reflex ? kFlip22 : kNone;
  return (x == a || x == b) ? kFlip22 : kNone;
}
#undef GG_HULL_SIGN
