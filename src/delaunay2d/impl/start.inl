// The 2D Triangulator's start (triangulator.inl): the first triangle and its three infinite
// neighbours, or a given triangulation (the digital method's sketch, DynamicDelaunay2d's kept
// one), with every other point located in it.

// The first triangle and its three infinite neighbours, in slots 0 to 3.
inline void Triangulator::write_first() {
  const std::int32_t a = P_.first[0], b = P_.first[1], c = P_.first[2], I = m_;
  const std::int32_t B = std::int32_t(base_);
  auto e = [B](std::int32_t s, int k) { return enc(B + s, k); };
  // slot 0 (a,b,c); slot 1 (c,b,I) across bc; slot 2 (a,c,I) across ca; slot 3 (b,a,I).
  const Tri first[4] = {{{a, b, c}, {e(1, 2), e(2, 2), e(3, 2)}, -1, 0},
                        {{c, b, I}, {e(3, 1), e(2, 0), e(0, 0)}, -1, 0},   // (b,I) (I,c) (c,b)
                        {{a, c, I}, {e(1, 1), e(3, 0), e(0, 1)}, -1, 0},   // (c,I) (I,a) (a,c)
                        {{b, a, I}, {e(2, 1), e(1, 0), e(0, 2)}, -1, 0}};  // (a,I) (I,b) (b,a)
  ex_.from_host(first, 4, tri_.data());
  ntri_ = 4;
}

// The same, with every other point located in it.
inline void Triangulator::start() {
  ready_rounds();
  write_first();
  const std::int32_t a = P_.first[0], b = P_.first[1], c = P_.first[2];
  const std::int32_t B = std::int32_t(base_);
  const Geo g = g_;
  std::int32_t* loc = loc_.data();
  const Tri* tri = tri_.data();
  Counters* ctr = ctr_.data();
  ex_.for_each_index(
      m_, GG_LAMBDA(std::int64_t i) {
        const std::int32_t q = std::int32_t(i);
        if (q == a || q == b || q == c) {
          loc[q] = -1;
          return;
        }
        std::int32_t found = -1;
        for (std::int32_t t = 0; t < 4 && found < 0; ++t)
          if (inside_ext(g, tri[t].v, q)) found = B + t;
        loc[q] = found;
        if (found < 0) atomic_add(&ctr->lost, std::int64_t(1));
      });
  nun_ = ex_.compact_indices(
      m_, GG_LAMBDA(std::int64_t i) { return loc[i] >= 0; }, un_.data());
  check_lost();
}

// The same from a given triangulation (the digital method's sketch, issue 20) instead of the
// first triangle: tris, counter-clockwise triangles of prepared indices covering the convex
// hull of their vertices with each directed edge once, gets its hull edges joined to the
// infinity vertex (2k - 2 slots for its k vertices, as the insertions would have left); the
// other points are located by walks; then the whole of it is flipped until Delaunay, and the
// batches insert the rest as they do after start(). P.kernel must lie inside it.
// start_delaunay: the start is already the Delaunay triangulation of its vertices under the
// perturbation, flat hull triangles included (DynamicDelaunay2d's kept one): its edges are not
// tested (on a grid every test is a cocircular one, decided by the exact stage).
inline void Triangulator::run_from(const std::int32_t* tris, const std::int32_t* twin,
                                   std::int64_t f, const std::int32_t* near, bool peel_flats,
                                   bool start_delaunay) {
  auto t0 = clock::now();
  start_from(tris, twin, f, near, start_delaunay);
  phase("start", t0);
  t0 = clock::now();
  remaining_ = nun_;
  while (remaining_ > 0) batch();
  phase("insert", t0);
  t0 = clock::now();
  if (!peel_flats) return;
  peel();
  phase("peel", t0);
}

// All in executor memory: tris (3 f), twin (per half-edge 3t + k, vertex k to k + 1: its
// reverse or -1), near (per prepared point, a start vertex near it or -1, where its walk
// begins; or null). The records are built on the executor: the hull edges numbered by a scan
// in half-edge order, each vertex's outgoing and incoming hull edge found by scatter.
// The start as the walks read it (mesh/walk.hpp): positions from the slot base.
struct StartTriangles {
  using Simplex = Tri;
  Geo g;
  const Tri* tri;
  std::int32_t base;
  GG_HD Tri at(std::int64_t t) const { return tri[t]; }
  GG_HD bool beyond(const Tri& T, int k, std::int32_t q) const {
    return orient_ext(g, T.v[(k + 1) % 3], T.v[(k + 2) % 3], q) < 0;
  }
  GG_HD std::int64_t across(const Tri& T, int k) const { return simplex_of(T.n[k]) - base; }
  GG_HD bool holds(std::int64_t t, std::int32_t q) const { return inside_ext(g, tri[t].v, q); }
};
// Where a point's walk starts: a triangle of its hint's (a start vertex near it), else the
// first; none for the start's own vertices (used).
struct WalkFrom {
  const std::int32_t* near;
  const std::int8_t* used;
  const std::int32_t* slot_of;
  GG_HD std::int64_t operator()(std::int32_t q) const {
    if (used[q]) return -2;
    const std::int32_t v = near ? near[q] : -1;
    return v >= 0 && used[v] ? slot_of[v] : 0;
  }
};

inline void Triangulator::start_from(const std::int32_t* tris, const std::int32_t* twin,
                                     std::int64_t f, const std::int32_t* near,
                                     bool start_delaunay) {
  ready_rounds();
  const std::int32_t I = m_, B = std::int32_t(base_);
  const std::int64_t nh = 3 * f;
  auto in = ex_.template alloc<std::int8_t>(std::size_t(m_));
  auto outs = ex_.template alloc<std::int32_t>(std::size_t(m_));
  auto ins = ex_.template alloc<std::int32_t>(std::size_t(m_));
  auto from = ex_.template alloc<std::int32_t>(std::size_t(m_));
  auto hpos = ex_.template alloc<std::int64_t>(std::size_t(nh + 1));
  std::int8_t* used = in.data();
  std::int32_t* out_slot = outs.data();
  std::int32_t* in_slot = ins.data();
  std::int32_t* slot_of = from.data();
  std::int64_t* pos = hpos.data();
  ex_.fill(used, m_, std::int8_t(0));
  ex_.fill(out_slot, m_, std::int32_t(-1));
  ex_.fill(in_slot, m_, std::int32_t(-1));
  ex_.fill(slot_of, m_, std::numeric_limits<std::int32_t>::max());
  ex_.exclusive_scan_of(
      nh + 1, GG_LAMBDA(std::int64_t e)->std::int64_t { return e < nh && twin[e] < 0; }, pos);
  std::int64_t nb = 0;
  ex_.to_host(pos + nh, 1, &nb);
  if (f + nb > tmax_)
    throw Error(ErrorCode::Internal, "start triangulation: " + std::to_string(f + nb) +
                                         " slots for at most " + std::to_string(tmax_));
  Tri* tri = tri_.data();
  ex_.for_each_index(
      f, GG_LAMBDA(std::int64_t t) {
        Tri T;
        for (int k = 0; k < 3; ++k) {
          T.v[k] = tris[3 * t + k];
          used[T.v[k]] = 1;
          atomic_min(&slot_of[T.v[k]], std::int32_t(t));
        }
        T.stamp = -1, T.pair = 0;
        for (int k = 0; k < 3; ++k) {
          const std::int64_t e = 3 * t + (k + 1) % 3;  // the edge opposite vertex k
          const std::int32_t o = twin[e];
          if (o >= 0) {
            T.n[k] = enc(B + o / 3, (o % 3 + 2) % 3);
          } else {  // a hull edge a->b: the infinite triangle (b, a, I) across
            const std::int32_t slot = std::int32_t(f + pos[e]);
            T.n[k] = enc(B + slot, 2);
            out_slot[T.v[(k + 1) % 3]] = slot, in_slot[T.v[(k + 2) % 3]] = slot;
          }
        }
        tri[t] = T;
      });
  // Each hull vertex has one outgoing and one incoming hull edge: as many of each as edges.
  auto cnt = ex_.template alloc<std::int64_t>(3);
  ex_.transform_reduce_into(
      m_, GG_LAMBDA(std::int64_t v)->std::int64_t { return out_slot[v] >= 0; }, std::int64_t(0),
      thrust::plus<std::int64_t>(), cnt.data());
  ex_.transform_reduce_into(
      m_, GG_LAMBDA(std::int64_t v)->std::int64_t { return in_slot[v] >= 0; }, std::int64_t(0),
      thrust::plus<std::int64_t>(), cnt.data() + 1);
  ex_.transform_reduce_into(
      m_, GG_LAMBDA(std::int64_t v)->std::int64_t { return used[v]; }, std::int64_t(0),
      thrust::plus<std::int64_t>(), cnt.data() + 2);
  std::int64_t c[3];
  ex_.to_host(cnt.data(), 3, c);
  if (c[0] != nb || c[1] != nb)
    throw Error(ErrorCode::Internal, "start triangulation: its boundary passes a vertex twice");
  const std::int64_t k = c[2];
  if (f + nb != 2 * k - 2)
    throw Error(ErrorCode::Internal, "start triangulation: " + std::to_string(f + nb) +
                                         " slots for " + std::to_string(k) +
                                         " vertices (a triangulation of a disk has 2k - 2)");
  ex_.for_each_index(
      nh, GG_LAMBDA(std::int64_t e) {
        if (twin[e] >= 0) return;
        const std::int64_t t = e / 3;
        const int j = int(e % 3);  // a = v[j] -> b = v[j + 1]; opposite vertex j + 2
        const std::int32_t a = tris[e], b = tris[3 * t + (j + 1) % 3];
        Tri X;
        X.v[0] = b, X.v[1] = a, X.v[2] = I;
        X.n[2] = enc(B + std::int32_t(t), (j + 2) % 3);
        X.n[0] = enc(B + in_slot[a], 1);   // across (a, I): the hull edge ending at a
        X.n[1] = enc(B + out_slot[b], 0);  // across (I, b): the hull edge starting at b
        X.stamp = -1, X.pair = 0;
        tri[f + pos[e]] = X;
      });
  ntri_ = f + nb;
  // The other points, each located by a walk from a triangle of its hint's (a slot of the
  // start), else from the first (mesh/walk.hpp).
  std::int32_t* loc = loc_.data();
  const std::int64_t nt = ntri_;
  const mesh::WalkCounts w =
      mesh::locate_by_walks<3>(ex_, m_, nt, StartTriangles{g_, tri, B},
                               WalkFrom{near, used, slot_of}, B, loc, &ctr_.data()->lost);
  mesh::put_walk_counts(st_, w);
  nun_ = ex_.compact_indices(
      m_, GG_LAMBDA(std::int64_t i) { return loc[i] >= 0; }, un_.data());
  check_lost();
  if (start_delaunay) return;
  // Every slot's edges tested, and flipped until Delaunay; the flips are logged, so the points
  // follow their triangles when the first batch relocates them.
  const mesh::WorkLists L = work_lists();
  std::int32_t* act = L.current(round_ + 1);
  std::int64_t* len = L.count(round_ + 1);
  ex_.for_each_index(
      nt, GG_LAMBDA(std::int64_t i) {
        if (i == 0) *len = nt;
        act[i] = list_entry(B + std::int32_t(i), -1);
      });
  nact_ = nt;
  flip_until_delaunay(false);
}

inline void Triangulator::check_lost() {
  Counters c = counters();
  if (c.lost)
    throw Error(ErrorCode::Internal,
                "internal error: " + std::to_string(c.lost) +
                    " point(s) could not be located; please report this input");
}
