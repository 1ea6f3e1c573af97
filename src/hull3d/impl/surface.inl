// The triangulated surface and its local changes, included inside
// gpugeom::hull3d::{cpu,cuda}_impl after geometry.inl.
//
// Facet f has vertices tv[3f..3f+2], counter-clockwise seen from outside (from s's far side),
// and neighbours to[3f+k] = 4 * (facet across the edge opposite vertex k) + (that facet's local
// index of its vertex opposite the same edge). The surface is closed: every edge has two
// facets. A removed facet has tv[3f] = -1. Slots are never reused.

// (The neighbour encoding comes from mesh/adjacency.hpp.)
using mesh::enc;
using mesh::loc_of;
using mesh::simplex_of;

struct Surface {
  std::int32_t* tv;
  std::int32_t* to;
  std::int32_t* stamp;  // round in which the slot last changed
  std::int32_t* remap;  // 3 per slot: where an outer edge of a changed slot went this round
  std::int32_t* deg;    // per vertex: its number of facets (0: not a vertex)
};

// The first tetrahedron t's four facets (a, b, c), (a, d, b), (b, d, c), (c, d, a), counter-
// clockwise from outside since d lies below (a, b, c), into fv (vertices) and fo (neighbours,
// found by matching reversed edges): where both schedules start (construct.inl, one_by_one.inl).
inline void first_facets(const Tetra& t, std::int32_t* fv, std::int32_t* fo) {
  const std::int32_t a = t.v[0], b = t.v[1], c = t.v[2], d = t.v[3];
  const std::int32_t v[12] = {a, b, c, a, d, b, b, d, c, c, d, a};
  std::copy(v, v + 12, fv);
  for (int f = 0; f < 4; ++f)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t x = v[3 * f + (k + 1) % 3], y = v[3 * f + (k + 2) % 3];
      for (int h = 0; h < 4; ++h)
        for (int j = 0; j < 3; ++j)
          if (v[3 * h + (j + 1) % 3] == y && v[3 * h + (j + 2) % 3] == x) fo[3 * f + k] = enc(h, j);
    }
}

// Splits facet f at p into child k = (p, v[k+1], v[k+2]) in slots c[k] = f, base, base + 1.
// split_rank / first_new give the child slots of neighbours split in the same round; a
// neighbour not split gets its back pointer from the child that now holds the shared edge.
GG_HD inline void split_facet(const Surface& S, std::int32_t f, std::int32_t p, std::int32_t base,
                              const std::int32_t* split_rank, std::int32_t first_new) {
  const std::int32_t v[3] = {S.tv[3 * f], S.tv[3 * f + 1], S.tv[3 * f + 2]};
  const std::int32_t o[3] = {S.to[3 * f], S.to[3 * f + 1], S.to[3 * f + 2]};
  const std::int32_t c[3] = {f, base, base + 1};
  for (int k = 0; k < 3; ++k) {
    const std::int32_t t = c[k];
    S.tv[3 * t] = p;
    S.tv[3 * t + 1] = v[(k + 1) % 3];
    S.tv[3 * t + 2] = v[(k + 2) % 3];
    S.to[3 * t + 1] = enc(c[(k + 1) % 3], 2);
    S.to[3 * t + 2] = enc(c[(k + 2) % 3], 1);
    const std::int32_t nb = simplex_of(o[k]);
    const int j = loc_of(o[k]);
    const std::int32_t r = split_rank[nb];
    if (r >= 0) {
      S.to[3 * t] = enc(j == 0 ? nb : first_new + 2 * r + (j - 1), 0);
    } else {
      S.to[3 * t] = o[k];
      S.to[3 * nb + j] = enc(t, 0);
    }
  }
  S.deg[p] = 3;
  for (int k = 0; k < 3; ++k) atomic_add(S.deg + v[k], 1);  // each old vertex gains edge p-v
}

// The 2-2 flip of the edge opposite vertex k of facet f (phase 1 of 2): with f = (c, a, b)
// from k and its neighbour g = (d, b, a) from j, f becomes (c, a, d) and g becomes (d, b, c).
// Outer neighbour pointers of the two slots are copied as they were; phase 2 (fix_edge) points
// them at the final slots once every change of the round has recorded where its edges went.
GG_HD inline void flip22(const Surface& S, std::int32_t f, int k, std::int32_t round) {
  const std::int32_t e = S.to[3 * f + k];
  const std::int32_t g = simplex_of(e);
  const int j = loc_of(e);
  const int k1 = (k + 1) % 3, k2 = (k + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
  const std::int32_t c = S.tv[3 * f + k], a = S.tv[3 * f + k1], b = S.tv[3 * f + k2];
  const std::int32_t d = S.tv[3 * g + j];
  const std::int32_t f_bc = S.to[3 * f + k1], f_ca = S.to[3 * f + k2];
  const std::int32_t g_ad = S.to[3 * g + j1], g_db = S.to[3 * g + j2];
  S.tv[3 * f] = c, S.tv[3 * f + 1] = a, S.tv[3 * f + 2] = d;
  S.to[3 * f] = g_ad, S.to[3 * f + 1] = enc(g, 1), S.to[3 * f + 2] = f_ca;
  S.tv[3 * g] = d, S.tv[3 * g + 1] = b, S.tv[3 * g + 2] = c;
  S.to[3 * g] = f_bc, S.to[3 * g + 1] = enc(f, 1), S.to[3 * g + 2] = g_db;
  S.remap[3 * f + k2] = enc(f, 2);
  S.remap[3 * g + j1] = enc(f, 0);
  S.remap[3 * f + k1] = enc(g, 0);
  S.remap[3 * g + j2] = enc(g, 2);
  S.stamp[f] = round, S.stamp[g] = round;
  atomic_add(S.deg + a, -1);
  atomic_add(S.deg + b, -1);
  atomic_add(S.deg + c, 1);
  atomic_add(S.deg + d, 1);
}

GG_HD inline int local_of(const Surface& S, std::int32_t f, std::int32_t v) {
  return S.tv[3 * f] == v ? 0 : S.tv[3 * f + 1] == v ? 1 : 2;
}

// The three facets around a degree-3 vertex x, given facet f and x's local index lx in it:
// f, then the next two counter-clockwise around x.
GG_HD inline void fan3(const Surface& S, std::int32_t f, int lx, std::int32_t* F, int* L) {
  F[0] = f, L[0] = lx;
  for (int i = 1; i < 3; ++i) {
    // Across the edge (tv[l+2], x), opposite tv[l+1], lies the next facet counter-clockwise;
    // there x follows the vertex opposite the shared edge.
    const std::int32_t e = S.to[3 * F[i - 1] + (L[i - 1] + 1) % 3];
    F[i] = simplex_of(e);
    L[i] = (loc_of(e) + 1) % 3;
  }
}

// The 3-1 flip removing vertex x (degree 3) of facet f at local lx: f becomes the triangle of
// the three outer edges, the other two slots are removed (phase 1 of 2, as flip22).
GG_HD inline void remove3(const Surface& S, std::int32_t f, int lx, std::int32_t round) {
  std::int32_t F[3];
  int L[3];
  fan3(S, f, lx, F, L);
  const std::int32_t x = S.tv[3 * f + lx];
  std::int32_t v[3], o[3];
  for (int i = 0; i < 3; ++i) {  // facet i's outer edge runs v[i] -> v[i+1]
    v[i] = S.tv[3 * F[i] + (L[i] + 1) % 3];
    o[i] = S.to[3 * F[i] + L[i]];
  }
  // New facet (v0, v1, v2): vertex k's opposite edge is facet (k+1)'s outer edge.
  for (int k = 0; k < 3; ++k) {
    S.tv[3 * f + k] = v[k];
    S.to[3 * f + k] = o[(k + 1) % 3];
    S.remap[3 * F[(k + 1) % 3] + L[(k + 1) % 3]] = enc(f, k);
    S.stamp[F[k]] = round;
    atomic_add(S.deg + v[k], -1);
  }
  S.tv[3 * F[1]] = -1;
  S.tv[3 * F[2]] = -1;
  S.deg[x] = 0;
}

// Phase 2 (mesh/flip_fix.hpp) for the outer edge (slot x, local l) of a changed facet; where a
// changed neighbour's edge went is in remap. Returns the final neighbour slot.
struct RemapStore {
  const Surface& S;
  GG_HD void set(std::int32_t f, int k, std::int32_t e) const { S.to[3 * f + k] = e; }
  GG_HD std::int32_t moved(std::int32_t outer) const {
    return S.remap[3 * simplex_of(outer) + loc_of(outer)];
  }
};
GG_HD inline std::int32_t fix_edge(const Surface& S, std::int32_t x, int l, std::int32_t round) {
  const std::int32_t old = S.to[3 * x + l];
  return mesh::fix_face(RemapStore{S}, x, l, old, S.stamp[simplex_of(old)] == round);
}
