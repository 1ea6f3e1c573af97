// A convex polyhedron cut down by half-spaces, one thread's work (internal; the Voronoi cells of
// issue 49, impl/cells.inl). A cell starts as a box and is cut by the bisector planes of its
// site's Voronoi neighbours, as Voro++ builds its cells, except that the neighbours are the exact
// ridges of the Delaunay tetrahedralisation (voronoi.inl), not a search of nearby points.
//
// - Coordinates are relative to the site, so the planes are x.n <= |n|^2 / 2 with n = q - p and
//   keep every digit the points have in common.
// - A vertex within 1e-12 of the cell's size from a cutting plane counts as on it: a plane
//   through a vertex (four or more cells meeting at a point, as in a lattice) leaves no sliver
//   face of area 10^-30 behind.
// - Each new vertex is computed once, from its edge taken in one direction (inside end first),
//   so the two faces that share it hold the same vertex; the cap face is ordered by a comparison
//   of cross products, not by angles from a math library: every operation is rounded on its own
//   (the *_rn helpers) and both executors give the same bits.
// - Storage is the caller's (CellStore): a thread's local arrays, or a slice of executor memory
//   for the rare cell that outgrows them. A cut that would pass a capacity sets `overflow` and
//   leaves the cell to be built again with more room.
#pragma once
#include <cstdint>

#include "base/hd.hpp"
#include "predicates/expansion.hpp"

namespace gpugeom::cells {

GG_HD inline double dot3(const double* a, const double* b) {
  using exact::add_rn;
  using exact::mul_rn;
  return add_rn(add_rn(mul_rn(a[0], b[0]), mul_rn(a[1], b[1])), mul_rn(a[2], b[2]));
}
GG_HD inline void cross3(const double* a, const double* b, double* c) {
  using exact::mul_rn;
  using exact::sub_rn;
  c[0] = sub_rn(mul_rn(a[1], b[2]), mul_rn(a[2], b[1]));
  c[1] = sub_rn(mul_rn(a[2], b[0]), mul_rn(a[0], b[2]));
  c[2] = sub_rn(mul_rn(a[0], b[1]), mul_rn(a[1], b[0]));
}

// The arrays a cell lives in: vcap vertices, fcap faces, ecap face-vertex entries (twice: the
// faces are rebuilt from one half into the other at every cut).
struct CellStore {
  double* x;             // 3 * vcap coordinates, relative to the site
  std::int32_t* ent;     // 2 * ecap: each face's vertices, counter-clockwise seen from outside
  std::int32_t* fstart;  // fcap: where each face's vertices start in the current half
  std::int32_t* flen;    // fcap
  std::int32_t* fplane;  // fcap: the plane each face lies in (the caller's numbering)
  std::int8_t* side;     // vcap: per vertex, -1 inside the cutting plane, 0 on it, 1 outside
  std::int32_t* remap;   // vcap: old vertex -> new
  std::int32_t* ea;      // vcap: per new vertex, its edge (inside end, outside end)
  std::int32_t* eb;      // vcap
  double* okey;          // fcap: the order of the cuts (cells.inl sorts the planes)
  std::int32_t* oidx;    // fcap
  int vcap, ecap, fcap;
};

struct ConvexCell {
  CellStore s;
  int nv = 0, nf = 0, half = 0;
  bool overflow = false;
  double r2 = 0;  // the largest squared distance of a vertex from the site

  // Whether the plane x.n = |n|^2 / 2 lies beyond every vertex (|n| / 2 > the farthest vertex's
  // distance, with room for rounding): a cut by it changes nothing, nor by any plane further.
  GG_HD bool beyond(const double* n) const { return dot3(n, n) / 4 > r2 * (1 + 1e-9); }

  GG_HD std::int32_t* faces_ent() const { return s.ent + half * s.ecap; }
  GG_HD const double* vertex(int i) const { return s.x + 3 * i; }
  GG_HD bool empty() const { return nf == 0; }

  // The box [lo, hi] (relative to the site); its faces are planes 0..5: 2 axis + (1 at hi).
  GG_HD void box(const double* lo, const double* hi) {
    overflow = s.vcap < 8 || s.fcap < 6 || s.ecap < 24;
    nv = nf = half = 0;
    if (overflow) return;
    for (int i = 0; i < 8; ++i) {
      s.x[3 * i] = (i & 1) ? hi[0] : lo[0];
      s.x[3 * i + 1] = (i & 2) ? hi[1] : lo[1];
      s.x[3 * i + 2] = (i & 4) ? hi[2] : lo[2];
    }
    nv = 8;
    r2 = 0;
    for (int i = 0; i < 8; ++i) r2 = fmax(r2, dot3(vertex(i), vertex(i)));
    // (corner i has bit k set where it is at the high end of axis k; each ring runs
    // counter-clockwise seen from outside)
    constexpr int ring[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    std::int32_t* e = faces_ent();
    for (int f = 0; f < 6; ++f) {
      s.fstart[f] = 4 * f, s.flen[f] = 4, s.fplane[f] = f;
      for (int k = 0; k < 4; ++k) e[4 * f + k] = ring[f][k];
    }
    nf = 6;
  }

  // Keeps the part where x.n <= c; the new face (if any) lies in plane `plane`.
  GG_HD void cut(const double* n, double c, std::int32_t plane) {
    using exact::add_rn;
    using exact::mul_rn;
    using exact::sub_rn;
    if (overflow || nf == 0) return;
    double size = 0;
    for (int i = 0; i < 3 * nv; ++i) size = fmax(size, fabs(s.x[i]));
    const double nn = fmax(fabs(n[0]), fmax(fabs(n[1]), fabs(n[2])));
    const double tol = 1e-12 * add_rn(mul_rn(3 * nn, size), fabs(c));
    bool any_in = false, any_out = false;
    for (int i = 0; i < nv; ++i) {
      const double d = sub_rn(dot3(vertex(i), n), c);
      const std::int8_t sd = d > tol ? 1 : (d < -tol ? -1 : 0);
      s.side[i] = sd;
      any_in |= sd < 0;
      any_out |= sd > 0;
    }
    if (!any_out) return;  // (the plane misses the cell or touches it)
    if (!any_in) {         // (nothing strictly inside: the cell is gone)
      nv = nf = 0;
      r2 = 0;
      return;
    }
    // New vertices, one per edge from inside to outside, found where it leaves a face.
    const std::int32_t* e = faces_ent();
    int nn_new = 0;
    for (int f = 0; f < nf; ++f) {
      const std::int32_t* r = e + s.fstart[f];
      const int m = s.flen[f];
      for (int k = 0; k < m; ++k) {
        const std::int32_t a = r[k], b = r[k + 1 < m ? k + 1 : 0];
        if (s.side[a] >= 0 || s.side[b] <= 0) continue;
        const int j = nv + nn_new++;
        if (j >= s.vcap) {
          overflow = true;
          return;
        }
        s.ea[j] = a, s.eb[j] = b;
        const double da = sub_rn(dot3(vertex(a), n), c), db = sub_rn(dot3(vertex(b), n), c);
        const double t = da / sub_rn(da, db);
        for (int d = 0; d < 3; ++d)
          s.x[3 * j + d] =
              add_rn(s.x[3 * a + d], mul_rn(t, sub_rn(s.x[3 * b + d], s.x[3 * a + d])));
      }
    }
    auto new_vertex = [&](std::int32_t a, std::int32_t b) {  // (a inside, b outside)
      for (int j = nv; j < nv + nn_new; ++j)
        if (s.ea[j] == a && s.eb[j] == b) return j;
      return -1;
    };
    // The faces, clipped, into the other half.
    std::int32_t* o = s.ent + (1 - half) * s.ecap;
    int at = 0, kept = 0;
    for (int f = 0; f < nf; ++f) {
      const std::int32_t* r = e + s.fstart[f];
      const int m = s.flen[f], from = at;
      for (int k = 0; k < m; ++k) {
        const std::int32_t a = r[k], b = r[k + 1 < m ? k + 1 : 0];
        if (at + 2 > s.ecap) {
          overflow = true;
          return;
        }
        if (s.side[a] <= 0) o[at++] = a;
        std::int32_t j = -2;
        if (s.side[a] < 0 && s.side[b] > 0) j = new_vertex(a, b);
        if (s.side[a] > 0 && s.side[b] < 0) j = new_vertex(b, a);
        if (j == -1) {  // (an edge one face has and its neighbour not: give up on this room)
          overflow = true;
          return;
        }
        if (j >= 0) o[at++] = j;
      }
      if (at - from < 3) {
        at = from;
        continue;
      }
      s.fstart[kept] = from, s.flen[kept] = at - from, s.fplane[kept] = s.fplane[f];
      ++kept;
    }
    // The cap: the vertices on the plane and the new ones, counter-clockwise round n.
    const int cap_from = at;
    for (int i = 0; i < nv + nn_new; ++i) {
      if (i < nv && s.side[i] != 0) continue;
      if (at >= s.ecap) {
        overflow = true;
        return;
      }
      o[at++] = i;
    }
    const int cm = at - cap_from;
    if (cm >= 3) {
      if (kept >= s.fcap) {
        overflow = true;
        return;
      }
      order_round(o + cap_from, cm, n);
      s.fstart[kept] = cap_from, s.flen[kept] = cm, s.fplane[kept] = plane;
      ++kept;
    } else {
      at = cap_from;
    }
    // Vertices outside go; the rest are renumbered in order, the new ones last.
    int w = 0;
    r2 = 0;
    for (int i = 0; i < nv + nn_new; ++i) {
      if (i < nv && s.side[i] > 0) continue;
      s.remap[i] = w;
      if (w != i)
        for (int d = 0; d < 3; ++d) s.x[3 * w + d] = s.x[3 * i + d];
      r2 = fmax(r2, dot3(vertex(w), vertex(w)));
      ++w;
    }
    for (int k = 0; k < at; ++k) o[k] = s.remap[o[k]];
    nv = w, nf = kept, half = 1 - half;
  }

  // Sorts m vertex indices counter-clockwise round the axis n through their mean (insertion
  // sort; a cap has a handful).
  GG_HD void order_round(std::int32_t* idx, int m, const double* n) const {
    using exact::add_rn;
    using exact::sub_rn;
    double cen[3] = {0, 0, 0};
    for (int k = 0; k < m; ++k)
      for (int d = 0; d < 3; ++d) cen[d] = add_rn(cen[d], vertex(idx[k])[d]);
    for (int d = 0; d < 3; ++d) cen[d] = cen[d] / m;
    // u: a direction in the plane; v = n x u
    int small = 0;
    for (int d = 1; d < 3; ++d)
      if (fabs(n[d]) < fabs(n[small])) small = d;
    double axis[3] = {0, 0, 0}, u[3], v[3];
    axis[small] = 1;
    cross3(n, axis, u);
    cross3(n, u, v);
    auto rel = [&](std::int32_t i, double* r) {
      for (int d = 0; d < 3; ++d) r[d] = sub_rn(vertex(i)[d], cen[d]);
    };
    auto half_of = [&](const double* r) {  // 0: angle in [0, pi), 1: [pi, 2 pi)
      const double y = dot3(r, v), x = dot3(r, u);
      return (y > 0 || (y == 0 && x > 0)) ? 0 : 1;
    };
    auto before = [&](std::int32_t i, std::int32_t j) {
      double a[3], b[3], ab[3];
      rel(i, a);
      rel(j, b);
      const int ha = half_of(a), hb = half_of(b);
      if (ha != hb) return ha < hb;
      cross3(a, b, ab);
      return dot3(ab, n) > 0;
    };
    for (int k = 1; k < m; ++k) {
      const std::int32_t key = idx[k];
      int j = k - 1;
      while (j >= 0 && before(key, idx[j])) {
        idx[j + 1] = idx[j];
        --j;
      }
      idx[j + 1] = key;
    }
  }

  // Volume, centroid (relative to the site) and, per face, its area: fans from each face's
  // first vertex, tetrahedra from the site (inside its cell).
  GG_HD double measure(double* centroid) const {
    using exact::add_rn;
    using exact::mul_rn;
    double six_v = 0, m[3] = {0, 0, 0};
    const std::int32_t* e = faces_ent();
    for (int f = 0; f < nf; ++f) {
      const std::int32_t* r = e + s.fstart[f];
      const double* a = vertex(r[0]);
      for (int k = 1; k + 1 < s.flen[f]; ++k) {
        const double *b = vertex(r[k]), *c = vertex(r[k + 1]);
        double bc[3];
        cross3(b, c, bc);
        const double det = dot3(a, bc);
        six_v = add_rn(six_v, det);
        for (int d = 0; d < 3; ++d)
          m[d] = add_rn(m[d], mul_rn(det, add_rn(add_rn(a[d], b[d]), c[d])));
      }
    }
    for (int d = 0; d < 3; ++d) centroid[d] = six_v > 0 ? m[d] / (4 * six_v) : 0;
    return six_v / 6;
  }
  GG_HD double face_area(int f) const {
    using exact::add_rn;
    using exact::sub_rn;
    const std::int32_t* r = faces_ent() + s.fstart[f];
    const double* a = vertex(r[0]);
    double sum[3] = {0, 0, 0};
    for (int k = 1; k + 1 < s.flen[f]; ++k) {
      double b[3], c[3], bc[3];
      for (int d = 0; d < 3; ++d)
        b[d] = sub_rn(vertex(r[k])[d], a[d]), c[d] = sub_rn(vertex(r[k + 1])[d], a[d]);
      cross3(b, c, bc);
      for (int d = 0; d < 3; ++d) sum[d] = add_rn(sum[d], bc[d]);
    }
    return sqrt(dot3(sum, sum)) / 2;
  }
};

}  // namespace gpugeom::cells
