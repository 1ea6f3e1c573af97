// A 2D Delaunay triangulation kept on the executor between calls (DynamicDelaunay2d, issue 47).
// Included inside gpugeom::del2d::{cpu,cuda}_impl after triangulate.inl.
//
// Kept: the input points in input order, the finite triangles in input indices with their
// neighbours, and the duplicate map. The triangles are the Delaunay triangulation of the
// perturbed points, flat triangles on the hull included (the Triangulator runs without its final
// peel): started from a peeled one, the flips would build the flat triangles again, one per
// round along each collinear hull edge (916 rounds for 1000 points into a 1000^2 grid). The
// results leave them out, as the peel would (it only turns them into infinite triangles). An
// insertion appends the new points, prepares the whole set again (validation, curve order,
// duplicates: one sort, the step that is still global), and runs the Triangulator from the kept
// triangulation (run_from_start): each new point is located by a walk from the old vertex before it
// on the curve, and the batches insert the new points; the kept triangles are Delaunay among the
// old points, so only the new points' neighbourhoods are tested and flipped. The result is a fresh
// triangulation's: the perturbation depends on the points alone, and the Delaunay triangulation of
// perturbed points is unique.

// Per half-edge 3t + k (vertex k to vertex k + 1) of nt triangles: its reverse's half-edge in the
// neighbour across (the triangle opposite vertex k + 2), -1 on the hull.
inline void twins_of_neighbours(Exec& ex, const std::int32_t* tri, const std::int32_t* nb,
                                std::int64_t nt, std::int32_t* twin) {
  ex.for_each_index(
      3 * nt, GG_LAMBDA(std::int64_t e) {
        const std::int64_t t = e / 3;
        const int k = int(e % 3);
        const std::int32_t u = nb[3 * t + (k + 2) % 3];
        std::int32_t r = -1;
        if (u >= 0) {
          const std::int32_t b = tri[3 * t + (k + 1) % 3];  // the reverse leaves from b
          for (int j = 0; j < 3; ++j)
            if (tri[3 * std::int64_t(u) + j] == b) r = std::int32_t(3 * std::int64_t(u) + j);
        }
        twin[e] = r;
      });
}

// The kept triangles as results: the flat ones dropped (exactly collinear vertices), -1 across
// an edge to one.
struct NonFlat {
  const std::int32_t* tri;
  const std::int32_t* nb;
  const double* xy;
  GG_HD bool live(std::int64_t t) const {
    const double* p[3];
    for (int k = 0; k < 3; ++k) p[k] = xy + 2 * std::int64_t(tri[3 * t + k]);
    if (pred::orient2d_fast(p[0], p[1], p[2])) return true;
    double scratch[kOrient2dScratch];
    return pred::orient2d(p[0], p[1], p[2], scratch) != 0;
  }
  GG_HD mesh::SimplexRecord<3> get(std::int64_t t) const {
    mesh::SimplexRecord<3> r;
    for (int k = 0; k < 3; ++k) r.v[k] = tri[3 * t + k], r.n[k] = nb[3 * t + k];
    return r;
  }
};

// The kept arrays (executor memory), and the kernel point of the first triangulation: strictly
// inside its first triangle, so inside every later hull (hulls only grow), it serves every
// later start (the kept triangulation's own first triangle may be too thin to place one in).
struct KeptArrays {
  typename Exec::template Buffer<double> xy;             // 2 n, input order
  typename Exec::template Buffer<std::int32_t> tri, nb;  // 3 nt each
  typename Exec::template Buffer<std::int32_t> dup;      // n, when ndup or nremoved > 0
  typename Exec::template Buffer<std::int8_t> gone;      // n (1: removed), when nremoved > 0
  std::int64_t n = 0, nt = 0, ndup = 0, nremoved = 0;
  std::int64_t nout = 0;  // triangles in the results (nt less the flat ones)
  double kernel[2] = {0, 0};
  // The duplicate map (kRemoved at removed points), or null where every point is a vertex.
  const std::int32_t* dup_map() const { return ndup || nremoved ? dup.data() : nullptr; }
  const std::int8_t* gone_map() const { return nremoved ? gone.data() : nullptr; }
};

// The triangles of the results (an extended lambda may not sit in kept_insert's lambda).
inline std::int64_t count_non_flat(Exec& ex, const KeptArrays& R) {
  const NonFlat s{R.tri.data(), R.nb.data(), R.xy.data()};
  auto cnt = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      R.nt, GG_LAMBDA(std::int64_t t)->std::int64_t { return s.live(t); }, std::int64_t(0),
      thrust::plus<std::int64_t>(), cnt.data());
  std::int64_t c = 0;
  ex.to_host(cnt.data(), 1, &c);
  return c;
}

// Triangles (finite ones, flat ones included) tested with the points at xy (n points) for a
// move: every triangle must be positive (flat ones: ordered by the perturbation), every hull
// edge must have a kernel point s strictly on its left (so the infinite triangles, cones from s,
// are positive too), and s must lie inside exactly one triangle: with every triangle positive
// the triangles then cover the plane once (the number of triangles over a point is the same for
// every point; a boundary that wound twice round s would cover s twice). s is placed inside the
// first triangle that is positive and not flat. The vertices of what is not positive are
// flagged in `out`. All exact, with the perturbation (s as index n: after any point it equals).
struct MoveTest {
  std::int64_t bad = 0;      // triangles and hull edges not positive
  std::int64_t holding = 0;  // triangles holding s
  bool placed = false;       // s placed
  double s[2] = {0, 0};
};
inline MoveTest test_moved(Exec& ex, const std::int32_t* tri, const std::int32_t* nb,
                           std::int64_t nt, const double* xy, std::int64_t n, std::int8_t* out) {
  MoveTest r;
  auto cnt = ex.template alloc<std::int64_t>(2);  // bad tests, triangles holding s
  auto d_best = ex.template alloc<std::int32_t>(1);
  std::int64_t* c = cnt.data();
  std::int32_t* best = d_best.data();
  ex.fill(c, 2, std::int64_t(0));
  ex.fill(best, 1, std::numeric_limits<std::int32_t>::max());
  ex.for_each_index(
      nt, GG_LAMBDA(std::int64_t t) {
        double scratch[kOrient2dScratch];
        std::int32_t v[3];
        const double* p[3];
        for (int k = 0; k < 3; ++k) v[k] = tri[3 * t + k], p[k] = xy + 2 * std::int64_t(v[k]);
        if (pred::orient2d_sos(p[0], v[0], p[1], v[1], p[2], v[2], scratch) <= 0) {
          for (int k = 0; k < 3; ++k) out[v[k]] = 1;
          atomic_add(&c[0], std::int64_t(1));
        } else if (pred::orient2d_fast(p[0], p[1], p[2]) ||
                   pred::orient2d(p[0], p[1], p[2], scratch) != 0) {
          atomic_min(&best[0], std::int32_t(t));
        }
      });
  std::int32_t b = 0;
  ex.to_host(best, 1, &b);
  if (b == std::numeric_limits<std::int32_t>::max()) return r;
  std::int32_t id[3];
  double q[3][2];
  ex.to_host(tri + 3 * std::int64_t(b), 3, id);
  for (int k = 0; k < 3; ++k) ex.to_host(xy + 2 * std::int64_t(id[k]), 2, q[k]);
  const double* V[3] = {q[0], q[1], q[2]};
  if (!kernel_point(V, id, std::int32_t(n), r.s)) return r;
  r.placed = true;
  const double s0 = r.s[0], s1 = r.s[1];
  const std::int32_t sid = std::int32_t(n);
  ex.for_each_index(
      nt, GG_LAMBDA(std::int64_t t) {
        double scratch[kOrient2dScratch];
        const double s[2] = {s0, s1};
        std::int32_t v[3];
        const double* p[3];
        for (int k = 0; k < 3; ++k) v[k] = tri[3 * t + k], p[k] = xy + 2 * std::int64_t(v[k]);
        std::int64_t bad = 0;
        bool holds = true;
        for (int k = 0; k < 3; ++k) {
          const int a = (k + 1) % 3, b = (k + 2) % 3;
          const bool left = pred::orient2d_sos(p[a], v[a], p[b], v[b], s, sid, scratch) > 0;
          holds = holds && left;
          if (nb[3 * t + k] < 0 && !left) ++bad, out[v[a]] = 1, out[v[b]] = 1;
        }
        if (bad) atomic_add(&c[0], bad);
        if (holds) atomic_add(&c[1], std::int64_t(1));
      });
  std::int64_t h[2];
  ex.to_host(c, 2, h);
  r.bad = h[0];
  r.holding = h[1];
  return r;
}

// How the new state is reached from the kept one.
enum class Update { Insert, Move, Remove };

// Prepared points of the kept ones not removed (R.gone), in input indices with the duplicate
// map widened to all n (mesh::to_input_indices): prepare(P) runs prepare on the gathered points.
template <class Prep>
inline void prepare_kept(Exec& ex, const KeptArrays& R, std::int64_t n, Prep prep) {
  if (!R.nremoved) {
    prep(R.xy.data(), n, [](Prepared&) {});
    return;
  }
  const auto L = mesh::gather_live<2>(ex, R.xy.data(), n, R.gone.data());
  prep(L.p.data(), L.count, [&](Prepared& P) {
    P.dup =
        mesh::to_input_indices(ex, L, P.orig.data(), P.m, P.duplicates ? P.dup.data() : nullptr, n);
  });
}

// Removal (issue 47): the kept triangles with the holes of the removed vertices filled
// (mesh/hole_refill.hpp) from D, the triangulation of the hole's vertices that stay and of the
// copies that take a removed vertex's place (flat triangles kept, as in the kept one). ok false
// where that cannot be done here (too few or collinear such vertices, pieces that do not fit,
// or a count that breaks Euler's relation for the m points left): the caller builds afresh.
struct Refill2d {
  typename Exec::template Buffer<std::int32_t> tri, nb;
  std::int64_t nt = 0;
  std::int64_t unmatched = 0;  // boundary edges D lacks (new hull edges, or a bad fit)
  bool ok = false;
};

// D's triangles and neighbours (input indices), from the nv points ids name. [synchronises]
inline bool hole_triangulation(Exec& ex, const double* xy, const std::int32_t* ids, std::int64_t nv,
                               typename Exec::template Buffer<std::int32_t>& tri,
                               typename Exec::template Buffer<std::int32_t>& nb, std::int64_t& nt) {
  auto d_p = ex.template alloc<double>(std::size_t(2 * nv));
  double* p = d_p.data();
  ex.for_each_index(
      nv, GG_LAMBDA(std::int64_t j) {
        p[2 * j] = xy[2 * std::int64_t(ids[j])], p[2 * j + 1] = xy[2 * std::int64_t(ids[j]) + 1];
      });
  bool got = false;
  try {
    Delaunay2dStats sd;
    triangulate_core(
        ex, p, nv, true, false, sd, [](Prepared&) {},
        [&](Prepared& P, typename Triangulator::Finished& f) {
          if (P.duplicates) return;  // (the hole's vertices are distinct points)
          tri = std::move(f.simplices);
          nb = std::move(f.neighbors);
          nt = f.count;
          got = true;
        },
        false);
  } catch (const Error& e) {
    if (e.code() == ErrorCode::DegenerateInput) return false;  // (collinear hole vertices)
    throw;
  }
  if (!got) return false;
  std::int32_t* t = tri.data();
  ex.for_each_index(
      3 * nt, GG_LAMBDA(std::int64_t e) { t[e] = ids[t[e]]; });
  return true;
}

// Hull edges (no neighbour) of nt triangles. [synchronises]
inline std::int64_t hull_edges(Exec& ex, const std::int32_t* nb, std::int64_t nt) {
  auto cnt = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      3 * nt, GG_LAMBDA(std::int64_t e)->std::int64_t { return nb[e] < 0; }, std::int64_t(0),
      thrust::plus<std::int64_t>(), cnt.data());
  std::int64_t c = 0;
  ex.to_host(cnt.data(), 1, &c);
  return c;
}

// now: per point, 1 where it goes now; xy: the points' places (D is built there); new_dup: the
// duplicate map after (a copy of a point that goes, -1 there, takes its place); m: the distinct
// points left; mark (or null): set at the vertices of the staying triangles across boundary
// edges D lacks (mesh::refill_holes).
inline Refill2d refill_2d(Exec& ex, const KeptArrays& K, const std::int8_t* now, const double* xy,
                          const std::int32_t* new_dup, std::int64_t m, Delaunay2dStats& st,
                          std::int8_t* mark = nullptr) {
  Refill2d out;
  const std::int64_t n = K.n;  // (a removal keeps every index)
  auto d_hole = ex.template alloc<std::int8_t>(std::size_t(K.nt));
  const std::int64_t nh = mesh::hole_flags<3>(ex, K.tri.data(), K.nt, now, d_hole.data());
  if (nh == 0) {  // only points that were no vertices: the triangles stay
    out.tri = ex.template alloc<std::int32_t>(std::size_t(3 * K.nt));
    out.nb = ex.template alloc<std::int32_t>(std::size_t(3 * K.nt));
    ex.copy(K.tri.data(), 3 * K.nt, out.tri.data());
    ex.copy(K.nb.data(), 3 * K.nt, out.nb.data());
    out.nt = K.nt;
    out.ok = true;
    return out;
  }
  auto d_ids = ex.template alloc<std::int32_t>(std::size_t(n));
  const std::int64_t nv = mesh::hole_vertices<3>(ex, K.tri.data(), K.nt, d_hole.data(), now,
                                                 K.dup_map(), new_dup, n, d_ids.data());
  st.hole_vertices = nv;
  typename Exec::template Buffer<std::int32_t> dtri, dnb;
  std::int64_t dnt = 0;
  if (nv < 3 || !hole_triangulation(ex, xy, d_ids.data(), nv, dtri, dnb, dnt)) return out;
  auto f = mesh::refill_holes<3>(ex, K.tri.data(), K.nb.data(), K.nt, d_hole.data(), dtri.data(),
                                 dnb.data(), dnt, false, mark);
  st.hole_triangles = f.inside;
  out.unmatched = f.unmatched;
  // Euler: a triangulation of m points with h hull edges has 2m - 2 - h triangles
  if (!f.ok || f.count != 2 * m - 2 - hull_edges(ex, f.n.data(), f.count)) return out;
  out.tri = std::move(f.v);
  out.nb = std::move(f.n);
  out.nt = f.count;
  out.ok = true;
  return out;
}

// A move's start (issue 47): the kept triangles with the points at their new places. Where a
// triangle turns over there (or a hull edge no longer has the kernel point on its left), its
// vertices are taken out, to be inserted again at their new places as new points: the holes
// they leave are filled at the new places by the triangles of D, the Delaunay triangulation of
// the hole's other vertices there, that fit in them (refill_2d, as a removal). D's triangles are
// positive at the new places by construction; where a fill does not fit (Euler's count, or a
// boundary edge D lacks that is no new hull edge), the staying triangles across the edges D
// lacks are taken into the hole too and D is made again. The filled triangles are then tested
// like the kept ones: every triangle positive and the kernel point covered once make them a
// triangulation (the covering argument of test_moved). A few rounds settle it; beyond
// kMoveRounds, or where more than an eighth of the points would go (a large displacement is no
// cheaper to repair), the caller triangulates afresh. m: the distinct points (the kept
// triangulation's vertices).
constexpr int kMoveRounds = 8;
struct MovedStart2d {
  typename Exec::template Buffer<std::int32_t> tri, nb;  // the refilled (empty: the kept ones)
  std::int64_t nt = 0;
  typename Exec::template Buffer<std::int8_t> out;  // n: 1 where taken out
  std::int64_t nout = 0;
  double kernel[2] = {0, 0};  // inside the start's hull at the new places
  bool ok = false;
};
inline MovedStart2d moved_start(Exec& ex, const KeptArrays& K, const double* xy, std::int64_t n,
                                std::int64_t m, Delaunay2dStats& st) {
  MovedStart2d M;
  M.out = ex.template alloc<std::int8_t>(std::size_t(n));
  auto d_grow = ex.template alloc<std::int8_t>(std::size_t(n));
  std::int8_t* out = M.out.data();
  const std::int8_t* grow = d_grow.data();
  ex.fill(out, n, std::int8_t(0));
  Refill2d f;
  const std::int32_t* tri = K.tri.data();
  const std::int32_t* nb = K.nb.data();
  std::int64_t nt = K.nt;
  bool grown = false;  // the last fill did not fit: its hole grew, fill again
  for (int round = 0; round < kMoveRounds; ++round) {
    st.move_rounds = round + 1;
    if (!grown) {
      const MoveTest t = test_moved(ex, tri, nb, nt, xy, n, out);
      if (!t.placed) return M;
      if (t.bad == 0) {
        M.ok = t.holding == 1;  // (else the boundary winds twice round s)
        M.kernel[0] = t.s[0], M.kernel[1] = t.s[1];
        M.tri = std::move(f.tri), M.nb = std::move(f.nb);
        M.nt = nt;
        return M;
      }
    }
    M.nout = mesh::count_flags(ex, out, n);
    st.move_taken_out = M.nout;
    if (M.nout > n / 8 || m - M.nout < 3) return M;
    ex.fill(d_grow.data(), n, std::int8_t(0));
    const auto t0 = std::chrono::steady_clock::now();
    f = refill_2d(ex, K, out, xy, K.dup_map(), m - M.nout, st, d_grow.data());
    st.phase_ms.push_back({"move_refill", ms_since(t0)});
    grown = !f.ok && f.unmatched > 0;
    if (!f.ok && !grown) return M;
    if (grown)
      ex.for_each_index(
          n, GG_LAMBDA(std::int64_t i) {
            if (grow[i]) out[i] = 1;
          });
    else
      tri = f.tri.data(), nb = f.nb.data(), nt = f.nt;
  }
  return M;
}

// The state for the n points in R.xy (the kept points with `add` appended, or all of them
// moved), built beside K: K is not touched, so a call that throws leaves it as it was.
// Insert: the new points go into the kept triangulation. Move: the kept triangulation with the
// vertices of turned-over triangles taken out (moved_start) is flipped until Delaunay, and those
// vertices go back in as new points; where that cannot be done, the points are triangulated
// afresh (counter "move_rebuilt").
inline KeptArrays kept_update(Exec& ex, const KeptArrays& K, KeptArrays R, std::int64_t n,
                              Update how, bool profile, Delaunay2dStats& st) {
  auto keep = [&](Prepared& P, typename Triangulator::Finished& f) {
    R.n = n;
    R.nt = f.count;
    R.ndup = P.duplicates;
    R.kernel[0] = P.kernel[0], R.kernel[1] = P.kernel[1];
    R.tri = std::move(f.simplices);
    R.nb = std::move(f.neighbors);
    if (P.duplicates || R.nremoved) R.dup = std::move(P.dup);
    R.nout = count_non_flat(ex, R);
  };
  auto fresh = [&] {
    prepare_kept(ex, R, n, [&](const double* xy, std::int64_t m, auto widen) {
      triangulate_core(ex, xy, m, true, profile, st, widen, keep, false);
    });
    if (R.nremoved) st.points = n, st.removed_points = R.nremoved;
    ex.sync();
    return std::move(R);
  };
  if (!K.n) return fresh();  // the first points
  // afresh from the points prepared here (a move or removal that cannot start from K)
  auto afresh = [&](Prepared& P) {
    triangulate_prepared(ex, P, profile, st, keep, false);
    ex.sync();
    return std::move(R);
  };
  auto t0 = std::chrono::steady_clock::now();
  Prepared P;
  prepare_kept(ex, R, n, [&](const double* xy, std::int64_t m, auto widen) {
    P = prepare(ex, xy, m, true);
    widen(P);
  });
  const std::int32_t* dup_map = P.duplicates || R.nremoved ? P.dup.data() : nullptr;
  st.points = n;
  st.distinct_points = P.m;
  st.duplicates = P.duplicates;
  if (R.nremoved) st.removed_points = R.nremoved;
  // the triangulation the Triangulator starts from: the kept one, or after a removal the refilled
  const std::int32_t* start_tri = K.tri.data();
  const std::int32_t* start_nb = K.nb.data();
  std::int64_t start_nt = K.nt;
  Refill2d filled;
  double kernel[2] = {K.kernel[0], K.kernel[1]};
  MovedStart2d moved;
  bool walks = how == Update::Insert;  // (points to locate: inserted, or a move's taken out)
  auto d_hint = ex.template alloc<std::int32_t>(how != Update::Remove ? std::size_t(n) : 0);
  if (how == Update::Remove) {
    const auto t1 = std::chrono::steady_clock::now();
    auto d_now = mesh::removed_now(ex, R.gone.data(), K.gone_map(), n);
    filled = refill_2d(ex, K, d_now.data(), R.xy.data(), dup_map, P.m, st);
    st.phase_ms.push_back({"refill", ms_since(t1)});
    st.remove_rebuilt = !filled.ok;
    if (!filled.ok) return afresh(P);
    start_tri = filled.tri.data(), start_nb = filled.nb.data(), start_nt = filled.nt;
    // The kernel point must lie inside the start's hull: the first build's is inside every
    // later one while points are only added or moved; after a removal the new first
    // triangle's is.
    kernel[0] = P.kernel[0], kernel[1] = P.kernel[1];
  } else if (how == Update::Insert) {
    st.inserted_points = P.m - (K.n - K.ndup - K.nremoved);
    mesh::curve_hints(ex, P.orig.data(), P.m, n, mesh::BelowIndex{std::int32_t(K.n)},
                      d_hint.data());
  } else {
    const bool same_points =
        P.duplicates == K.ndup && mesh::dup_changes(ex, K.dup_map(), dup_map, n) == 0;
    if (same_points) moved = moved_start(ex, K, R.xy.data(), n, P.m, st);
    st.move_rebuilt = !moved.ok;
    st.phase_ms.push_back({"move_start", ms_since(t0)});
    if (!moved.ok) return afresh(P);
    if (moved.tri.size())
      start_tri = moved.tri.data(), start_nb = moved.nb.data(), start_nt = moved.nt;
    kernel[0] = moved.kernel[0], kernel[1] = moved.kernel[1];
    if (moved.nout) {
      walks = true;
      st.move_reinserted = moved.nout;
      mesh::curve_hints(ex, P.orig.data(), P.m, n, mesh::NotFlagged{moved.out.data()},
                        d_hint.data());
    }
  }
  auto d_tri = ex.template alloc<std::int32_t>(std::size_t(3 * start_nt));  // (mapped in place)
  auto d_twin = ex.template alloc<std::int32_t>(std::size_t(3 * start_nt));
  ex.copy(start_tri, 3 * start_nt, d_tri.data());
  twins_of_neighbours(ex, start_tri, start_nb, start_nt, d_twin.data());
  ex.sync();
  st.phase_ms.push_back({"prepare", ms_since(t0)});
  // (a move's start is tested everywhere; an insertion's and a refill's are Delaunay)
  auto f = run_from_start(ex, P, n, d_tri.data(), start_nt, d_twin.data(),
                          walks ? d_hint.data() : nullptr, profile, st, kernel, false,
                          how != Update::Move);
  keep(P, f);
  ex.sync();
  return R;
}

// The kept points with `add` more appended (host memory, or executor memory when on_device), or
// all n replaced (move).
inline KeptArrays with_points(Exec& ex, const KeptArrays& K, const double* xy, std::int64_t add,
                              bool on_device, bool replace, Delaunay2dStats& st) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::int64_t keep = replace ? 0 : K.n, n = keep + add;
  KeptArrays R;
  R.xy = ex.template alloc<double>(std::size_t(2 * n));
  if (keep) ex.copy(K.xy.data(), 2 * keep, R.xy.data());
  if (add && on_device)
    ex.copy(xy, 2 * add, R.xy.data() + 2 * keep);
  else if (add)
    ex.from_host(xy, 2 * add, R.xy.data() + 2 * keep);
  R.gone = mesh::extend_flags(ex, K.gone_map(), K.n, n);
  R.nremoved = K.nremoved;
  st.phase_ms.push_back({"append", ms_since(t0)});
  return R;
}

class KeptOn final : public Kept {
 public:
  explicit KeptOn(const RunOptions& run) : run_(run) {}
  void insert(const double* xy, std::int64_t n, bool on_device, Delaunay2dStats& st) override {
    if (n == 0 && K_.n) return;
    Exec ex(run_);
    const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
    ::gpugeom::detail::require_device_memory(ex, K_.n + n, kLeastBytesPerPoint,
                                             "a 2D Delaunay triangulation", "points");
    KeptArrays R = with_points(ex, K_, xy, n, on_device, false, st);
    before_.commit(K_,
                   kept_update(ex, K_, std::move(R), K_.n + n, Update::Insert, run_.profile, st));
  }
  void move(const double* xy, bool on_device, Delaunay2dStats& st) override {
    Exec ex(run_);
    const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
    ::gpugeom::detail::require_device_memory(ex, K_.n, kLeastBytesPerPoint,
                                             "a 2D Delaunay triangulation", "points");
    KeptArrays R = with_points(ex, K_, xy, K_.n, on_device, true, st);
    before_.commit(K_, kept_update(ex, K_, std::move(R), K_.n, Update::Move, run_.profile, st));
  }
  void remove(const std::int32_t* idx, std::int64_t count, bool on_device,
              Delaunay2dStats& st) override {
    if (count == 0) return;
    Exec ex(run_);
    const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
    typename Exec::template Buffer<std::int32_t> up;
    if (!on_device) {
      up = ex.template alloc<std::int32_t>(std::size_t(count));
      ex.from_host(idx, count, up.data());
      idx = up.data();
    }
    auto gone = mesh::removal_flags(ex, K_.gone_map(), K_.n, idx, count);
    KeptArrays R = with_points(ex, K_, nullptr, 0, false, false, st);
    R.gone = std::move(gone);
    R.nremoved = K_.nremoved + count;
    before_.commit(K_, kept_update(ex, K_, std::move(R), K_.n, Update::Remove, run_.profile, st));
  }
  std::int64_t points() const override { return K_.n; }
  std::int64_t removed() const override { return K_.nremoved; }
  std::int64_t simplices() const override { return K_.nout; }
  // The results' triangles and neighbours (new executor arrays).
  static mesh::Compacted<Exec> compacted(Exec& ex, const KeptArrays& A) {
    return mesh::compact_live<3>(ex, A.nt, NonFlat{A.tri.data(), A.nb.data(), A.xy.data()});
  }
  mesh::Compacted<Exec> results(Exec& ex) const { return compacted(ex, K_); }
  void track_changes(bool on) override { before_.set(on); }
  bool has_changes() const override { return before_.held; }
  void host_changes(SimplexChanges& out) const override {
    Exec ex(run_);
    mesh::host_changes<3>(ex, compacted(ex, before_.arrays), compacted(ex, K_), out);
  }
  void device_changes(DeviceSimplexChanges& out) const override {
    Exec ex(run_);
    mesh::device_changes<3>(ex, compacted(ex, before_.arrays), compacted(ex, K_), out);
  }
  std::int64_t duplicates() const override { return K_.ndup; }
  void host_copy(Output& out) const override {
    Exec ex(run_);
    auto f = results(ex);
    out.num_triangles = f.count;
    out.num_duplicates = K_.ndup;
    out.triangles.resize(std::size_t(3 * f.count));
    out.neighbors.resize(std::size_t(3 * f.count));
    out.duplicate_of.resize(std::size_t(K_.n));
    ex.to_host(f.simplices.data(), 3 * f.count, out.triangles.data());
    ex.to_host(f.neighbors.data(), 3 * f.count, out.neighbors.data());
    if (K_.dup_map())
      ex.to_host(K_.dup.data(), K_.n, out.duplicate_of.data());
    else
      ex.fill_host(out.duplicate_of.data(), K_.n, std::int32_t(-1));
  }
  void device_copy(DeviceOutput& out) const override {
    Exec ex(run_);
    auto f = results(ex);
    auto dup = ex.template alloc<std::int32_t>(std::size_t(K_.n));
    if (K_.dup_map())
      ex.copy(K_.dup.data(), K_.n, dup.data());
    else
      ex.fill(dup.data(), K_.n, std::int32_t(-1));
    ex.sync();  // (the caller may read them, and free them on any stream)
    out.num_triangles = f.count;
    out.num_duplicates = K_.ndup;
    out.triangles = f.simplices.hand_over();
    out.neighbors = f.neighbors.hand_over();
    out.duplicate_of = dup.hand_over();
  }

  RunOptions run_;
  KeptArrays K_;
  ::gpugeom::detail::Before<KeptArrays> before_;
};
