// Phase 1's start (triangulator.inl): the first tetrahedron and its four infinite neighbours,
// or a kept tetrahedralisation (DynamicDelaunay3d), with every other point located in it.

// The kept store as the walks read it (mesh/walk.hpp).
struct StartTets {
  using Simplex = Tet;
  Geo g;
  const Tet* tet;
  GG_HD Tet at(std::int64_t t) const { return tet[t]; }
  GG_HD bool beyond(const Tet& T, int k, std::int32_t q) const {
    return orient_with(g, T.v, k, q) < 0;
  }
  GG_HD std::int64_t across(const Tet& T, int k) const { return simplex_of(T.n[k]); }
  GG_HD bool holds(std::int64_t t, std::int32_t q) const {
    return tet[t].v[0] >= 0 && inside_ext(g, tet[t].v, q);
  }
};
// Where a point's walk starts: a tetrahedron of its near vertex, else none (the scan); none
// for the kept vertices (in).
struct WalkFrom {
  const std::int32_t* near;
  const std::int8_t* in;
  const std::int32_t* slot_of;
  GG_HD std::int64_t operator()(std::int32_t q) const {
    if (in[q]) return -2;
    const std::int32_t h = near ? near[q] : -1;
    return h >= 0 && in[h] ? slot_of[h] : -1;
  }
};

// A kept tetrahedralisation (DynamicDelaunay3d, issue 47) in place of the first tetrahedron:
// kept (executor memory, `used` slots) is a store as phase 2 leaves it, the Delaunay
// tetrahedralisation of the perturbed points with its infinite tetrahedra and flat ones
// (vertices as input indices, kKeptInfinity for the infinity point; dead slots v[0] = -1;
// neighbours encoded as in the store, slot numbers kept). inv: input index -> prepared index;
// near: per prepared point not in it, a prepared vertex of it near it (-1: none). The other
// points are located by walks from a tetrahedron of their near vertex. g_.s must be the kept
// one's kernel point (strictly inside its hull).
inline void Triangulator::start_from(const Tet* kept, std::int64_t used, const std::int32_t* inv,
                                     const std::int32_t* near) {
  reserve(used + 4096);
  const std::int32_t I = m_;
  Tet* tet = tet_.data();
  auto d_in = ex_.template alloc<std::int8_t>(std::size_t(m_));
  auto d_slot = ex_.template alloc<std::int32_t>(std::size_t(m_));
  std::int8_t* in = d_in.data();
  std::int32_t* slot_of = d_slot.data();
  ex_.fill(in, m_, std::int8_t(0));
  ex_.fill(slot_of, m_, std::numeric_limits<std::int32_t>::max());
  ex_.for_each_index(
      used, GG_LAMBDA(std::int64_t t) {
        Tet T = kept[t];
        if (T.v[0] != -1)  // (not dead: kKeptInfinity may come first)
          for (int k = 0; k < 4; ++k) {
            const std::int32_t v = T.v[k] == kKeptInfinity ? I : inv[T.v[k]];
            T.v[k] = v;
            if (v != I) {
              in[v] = 1;
              atomic_min(&slot_of[v], std::int32_t(t));
            }
          }
        tet[t] = T;
      });
  Counters c{};
  c.used = used;
  ex_.from_host(&c, 1, ctr_.data());
  // The other points, each located by a walk from a tetrahedron of their near vertex
  // (mesh/walk.hpp).
  std::int32_t* loc = loc_.data();
  const mesh::WalkCounts w = mesh::locate_by_walks<4>(
      ex_, m_, used, StartTets{g_, tet}, WalkFrom{near, in, slot_of}, 0, loc, &ctr_.data()->lost);
  mesh::put_walk_counts(st_, w);
  nun_ = ex_.compact_indices(
      m_, GG_LAMBDA(std::int64_t i) { return loc[i] >= 0; }, un_.data());
  check_errors();
}

// Every tetrahedron of the store listed and flipped until stuck (a move's start, whose faces
// need not be locally Delaunay: flips mend most of them at a round's cost, where phase 2
// would splay every star they touch; what they cannot mend, phase 2 does). The points not in
// the store follow the flips through the log, as in a batch.
inline void Triangulator::flip_start() {
  const std::int64_t used = counters().used;
  if (used > list_cap_) grow_lists(used);
  const mesh::WorkLists L = work_lists();
  std::int32_t* act = L.current(round_ + 1);
  std::int64_t* len = L.count(round_ + 1);
  const Tet* tet = tet_.data();
  ex_.for_each_index(
      used, GG_LAMBDA(std::int64_t i) {
        if (i == 0) *len = used;
        act[i] = tet[i].v[0] >= 0 ? std::int32_t(i) : -1;
      });
  nact_ = used;
  carry_from_ = INT32_MAX;  // (no batch to carry the list into)
  flip_until_stuck();
  ex_.sync();
}

// The first tetrahedron (slot 0) and its four infinite neighbours (slots 1-4), linked: the
// start of both schedules (the batches', and the CPU's cavities: one_by_one.inl).
inline void Triangulator::first_five(Tet* t) const {
  const std::int32_t I = m_;
  for (int k = 0; k < 4; ++k) t[0].v[k] = first_.v[k];
  for (int k = 0; k < 4; ++k) {  // infinite tetrahedron k + 1 over face k (outward)
    std::int32_t f[3];
    face_of(t[0].v, k, f);
    t[k + 1] = Tet{{f[0], f[1], f[2], I}, {-1, -1, -1, -1}};
  }
  for (int a = 0; a < 5; ++a)  // adjacency by matching faces
    for (int k = 0; k < 4; ++k) {
      std::int32_t f[3];
      face_of(t[a].v, k, f);
      for (int b = 0; b < 5; ++b) {
        const int l = b == a ? -1 : opposite_of_face(t[b].v, f[0], f[1], f[2]);
        if (l >= 0) t[a].n[k] = enc(b, l);
      }
    }
}

// The first tetrahedron and its four infinite neighbours; every other point is located.
inline void Triangulator::start() {
  Tet t[5];
  first_five(t);
  ex_.from_host(t, 5, tet_.data());
  Counters c{};
  c.used = 5;
  ex_.from_host(&c, 1, ctr_.data());
  const Geo g = g_;
  std::int32_t* loc = loc_.data();
  const Tet* tet = tet_.data();
  Counters* ctr = ctr_.data();
  const std::int32_t a = t[0].v[0], b = t[0].v[1], cc = t[0].v[2], d = t[0].v[3];
  ex_.for_each_index(
      m_, GG_LAMBDA(std::int64_t i) {
        const std::int32_t q = std::int32_t(i);
        if (q == a || q == b || q == cc || q == d) {
          loc[q] = -1;
          return;
        }
        std::int32_t found = -1;
        for (std::int32_t s = 0; s < 5 && found < 0; ++s)
          if (inside_ext(g, tet[s].v, q)) found = s;
        loc[q] = found;
        if (found < 0) atomic_add(&ctr->lost, std::int64_t(1));
      });
  nun_ = ex_.compact_indices(
      m_, GG_LAMBDA(std::int64_t i) { return loc[i] >= 0; }, un_.data());
  check_errors();
}

inline void Triangulator::check_errors() {
  const Counters c = counters();
  if (c.lost || c.errors)
    throw Error(ErrorCode::Internal,
                "internal error: " + std::to_string(c.lost) + " point(s) could not be located, " +
                    std::to_string(c.errors) + " face(s) lost; please report this input");
}
