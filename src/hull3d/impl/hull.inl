// The whole computation: checks, construction, Flip-Flop, and the hull of the extreme points
// when the first hull had vertices that are not extreme. Included inside
// gpugeom::hull3d::{cpu,cuda}_impl after flipflop.inl.
//
// With simulation of simplicity the first pass gives the hull of the perturbed points. Its
// vertices include every extreme point, and may also include points the perturbation moved
// just outside: points inside a flat face or on a hull edge, and copies of a vertex. Each
// vertex is therefore tested exactly on its fan (flat fan: inside a face; two neighbours on a
// line through it: inside an edge), copies are merged, and when anything was dropped a second
// pass builds the hull of the extreme points alone, where every vertex is extreme and no
// facet is degenerate.

using Facets = mesh::Compacted<Exec>;

// The surface as the output step reads it: every facet not removed, named by its vertices'
// curve positions (the points are in curve order) for the output's order.
struct LiveFacets {
  const std::int32_t* tv;
  const std::int32_t* to;
  GG_HD bool live(std::int64_t f) const { return tv[3 * f] >= 0; }
  GG_HD void prefetch(std::int64_t f) const { prefetch_on_host(tv + 3 * f); }
  GG_HD void order_names(std::int64_t f, std::int32_t* w) const {
    for (int k = 0; k < 3; ++k) w[k] = tv[3 * f + k];
  }
  GG_HD mesh::SimplexRecord<3> get(std::int64_t f) const {
    mesh::SimplexRecord<3> r;
    for (int k = 0; k < 3; ++k) r.v[k] = tv[3 * f + k], r.n[k] = mesh::simplex_of(to[3 * f + k]);
    return r;
  }
};

// Live facets of the final surface, renumbered, with neighbours among them, in one order that
// depends on the facets alone (mesh/compact.hpp: each turned to start at its vertex first on the
// curve, sorted by their first two vertices): the slots follow the schedule, the rounds' on
// either executor or the CPU's points one by one, and the output must not.
inline Facets compact(Exec& ex, std::int64_t used, const std::int32_t* tv, const std::int32_t* to,
                      std::int64_t n) {
  return mesh::compact_live_sorted<3>(ex, used, LiveFacets{tv, to}, n);
}

// n_input: the caller's point count, for messages.
inline Facets one_pass(Exec& ex, const double* pts, std::int64_t n, Hull3dStats& st,
                       std::int64_t n_input) {
  auto t0 = Clock::now();
  const Tetra t = first_tetrahedron(ex, pts, n, n_input);
  st.phase_ms.emplace_back("prepare", ms_since(t0));
  t0 = Clock::now();
  if constexpr (Exec::backend == Backend::Cpu) {
    // The CPU's own schedule (one_by_one.inl), whose 2n - 4 slots the encoding must hold (the
    // rounds' store grows with the hull instead: beyond 2^28 points they take over).
    if (!ex.tuning().hull3d.rounds && 2 * n - 4 <= kMaxFacetSlots) {
      typename Exec::template Buffer<std::int32_t> tv, to;
      const std::int64_t used = insert_one_by_one(ex, pts, n, t, tv, to, st);
      st.phase_ms.emplace_back("insert", ms_since(t0));
      t0 = Clock::now();
      Facets out = compact(ex, used, tv.data(), to.data(), n);
      st.phase_ms.emplace_back("output", ms_since(t0));
      return out;
    }
  }
  PassState S(ex, pts, n, t.s, st);
  {
    Constructor C(S, t);
    C.run();
  }
  ex.sync();
  st.phase_ms.emplace_back("construct", ms_since(t0));
  t0 = Clock::now();
  {
    FlipFlop F(S);
    F.run();
  }
  Facets out = compact(ex, S.used, S.tv.data(), S.to.data(), n);
  ex.sync();
  st.phase_ms.emplace_back("flip", ms_since(t0));
  st.exact_predicates += S.counters().exact_all;
  return out;
}

// Is vertex v (first corner e0 = 4 * facet + local) extreme? A flat fan means v lies inside a
// face; two neighbours on a line through v that v lies between mean it lies inside an edge.
// Neighbours with v's coordinates (copies) are skipped. The fan is walked once into a small
// array when it fits (the checks then read it, not a chain of neighbour pointers per step);
// larger fans are walked in place.
struct ExtremeTest {
  static constexpr int kFanMax = 24;
  const double* p;
  const std::int32_t* tris;
  const std::int32_t* nbrs;
  GG_HD std::int32_t next_corner(std::int32_t e) const {  // the next facet around the vertex
    const std::int32_t f = e >> 2;
    const int l = e & 3;
    const std::int32_t v = tris[3 * f + l], g = nbrs[3 * f + (l + 1) % 3];
    const int m = tris[3 * g] == v ? 0 : tris[3 * g + 1] == v ? 1 : 2;
    return 4 * g + m;
  }
  GG_HD std::int32_t nb(std::int32_t e) const { return tris[3 * (e >> 2) + ((e & 3) + 1) % 3]; }
  GG_HD const double* at(std::int32_t v) const { return p + 3 * std::int64_t(v); }

  // The fan as an array of neighbour indices (copies left out).
  struct ArrayFan {
    const ExtremeTest& t;
    const std::int32_t* w;
    int m;
    template <class F>  // f(position, neighbour) until it returns false
    GG_HD void each(F f) const {
      for (int i = 0; i < m; ++i)
        if (!f(i, t.at(w[i]))) return;
    }
    template <class F>  // the same over the positions after `from`
    GG_HD void each_after(int from, F f) const {
      for (int i = from + 1; i < m; ++i)
        if (!f(i, t.at(w[i]))) return;
    }
  };
  // The fan walked in place (positions are corners).
  struct WalkFan {
    const ExtremeTest& t;
    const double* pv;
    std::int32_t e0;
    template <class F>
    GG_HD void each(F f) const {
      std::int32_t e = e0;
      do {
        const double* w = t.at(t.nb(e));
        if (!same_point(w, pv) && !f(e, w)) return;
        e = t.next_corner(e);
      } while (e != e0);
    }
    template <class F>
    GG_HD void each_after(std::int32_t from, F f) const {
      for (std::int32_t e = t.next_corner(from); e != e0; e = t.next_corner(e)) {
        const double* w = t.at(t.nb(e));
        if (!same_point(w, pv) && !f(e, w)) return;
      }
    }
  };

  template <class Fan>
  GG_HD static bool judge(const double* pv, const Fan& fan, double* s) {
    const double *a = nullptr, *b = nullptr;  // a: a neighbour; b: one off the line va
    std::int32_t at_a = -1, at_b = -1;        // (their positions in the fan)
    fan.each([&](std::int32_t at, const double* w) {
      if (!a) return a = w, at_a = at, true;
      if (collinear3(pv, a, w)) return true;
      b = w, at_b = at;
      return false;
    });
    if (!b) return false;  // every neighbour a copy or on one line: degenerate fan
    bool flat = true;
    fan.each([&](std::int32_t at, const double* w) {
      // (a and b themselves are skipped: orient3d proves their zero by its exact stage, twice a
      // vertex, which was most of this test's time on a sphere)
      if (at == at_a || at == at_b) return true;
      flat = pred::orient3d(pv, a, b, w, s) == 0;
      return flat;
    });
    if (flat) return false;
    bool in_edge = false;
    fan.each([&](std::int32_t px, const double* x) {
      fan.each_after(px, [&](std::int32_t, const double* y) {
        if (!collinear3(x, pv, y)) return true;
        for (int d = 0; d < 3; ++d)
          if (x[d] != y[d]) {
            in_edge = (x[d] < pv[d] && pv[d] < y[d]) || (y[d] < pv[d] && pv[d] < x[d]);
            break;
          }
        return !in_edge;
      });
      return !in_edge;
    });
    return !in_edge;
  }

  GG_HD bool operator()(std::int32_t v, std::int32_t e0, double* s) const {
    const double* pv = at(v);
    std::int32_t w[kFanMax];
    int m = 0;
    bool fits = true;
    std::int32_t e = e0;
    do {
      const std::int32_t x = nb(e);
      if (!same_point(at(x), pv)) {
        if (m == kFanMax) {
          fits = false;
          break;
        }
        w[m++] = x;
      }
      e = next_corner(e);
    } while (e != e0);
    if (fits) return judge(pv, ArrayFan{*this, w, m}, s);
    return judge(pv, WalkFan{*this, pv, e0}, s);
  }
};

struct Result {
  Facets facets;
  typename Exec::template Buffer<std::int32_t> vertices;  // in increasing order
  std::int64_t num_vertices = 0;
};

// The hull of n distinct points (of n_input given) on the executor, in their indices.
inline Result distinct_hull(Exec& ex, const double* pts, std::int64_t n, Hull3dStats& st,
                            std::int64_t n_input) {
  Result R;
  R.facets = one_pass(ex, pts, n, st, n_input);
  st.passes = 1;
  auto t0 = Clock::now();
  // The vertices, each with one corner, in index order.
  auto corner = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* cr = corner.data();
  ex.fill(cr, n, std::numeric_limits<std::int32_t>::max());
  const std::int32_t* tris = R.facets.simplices.data();
  const std::int32_t* nbrs = R.facets.neighbors.data();
  ex.for_each_index(
      3 * R.facets.count,
      GG_LAMBDA(std::int64_t i) { atomic_min(cr + tris[i], std::int32_t(4 * (i / 3) + i % 3)); });
  auto verts = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* vp = verts.data();
  const std::int64_t nv = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t v) { return cr[v] != std::numeric_limits<std::int32_t>::max(); },
      vp);
  // Exact extremeness, on bounded scratch slots.
  auto keep = ex.template alloc<std::int32_t>(std::size_t(nv));
  std::int32_t* kp = keep.data();
  {
    const ExtremeTest test{pts, tris, nbrs};
    ScratchSlots<Exec>(ex, std::min<std::int64_t>(nv, kExactSlots), kScratch)
        .run(
            ex, nv, GG_LAMBDA(std::int64_t j, double* s) {
              const std::int32_t v = vp[j];
              kp[j] = test(v, cr[v], s) ? v : -1;
            });
  }
  auto kept = ex.template alloc<std::int32_t>(std::size_t(nv));
  const std::int64_t nk = ex.copy_if(
      kp, nv, kept.data(), GG_LAMBDA(std::int32_t v) { return v >= 0; });
  st.first_pass_vertices = nv;
  st.nonextreme_vertices_dropped = nv - nk;
  ex.sync();
  st.phase_ms.emplace_back("extreme_test", ms_since(t0));
  if (nk == nv) {
    R.vertices = std::move(verts);
    R.num_vertices = nv;
    return R;
  }
  // Second pass on the extreme points alone.
  auto sub = ex.template alloc<double>(std::size_t(3 * nk));
  double* sp = sub.data();
  const std::int32_t* kv = kept.data();
  ex.for_each_index(
      3 * nk, GG_LAMBDA(std::int64_t i) { sp[i] = pts[3 * std::int64_t(kv[i / 3]) + i % 3]; });
  Facets F2 = one_pass(ex, sp, nk, st, nk);
  if (F2.count != 2 * nk - 4)  // Euler: every one of the nk extreme points must be a vertex
    throw Error(ErrorCode::Internal, "convex hull: the hull of the extreme points lost a vertex");
  std::int32_t* t2 = F2.simplices.data();
  ex.for_each_index(
      3 * F2.count, GG_LAMBDA(std::int64_t i) { t2[i] = kv[t2[i]]; });
  st.passes = 2;
  R.facets = std::move(F2);
  R.vertices = std::move(kept);
  R.num_vertices = nk;
  return R;
}

// The hull of n input points on the executor (read only), in input indices: validated, put in
// Hilbert order with duplicates merged (mesh/prepare.hpp), then distinct_hull. The curve order
// makes the construction's point reads local (the sphere 10^7 on the H100: 16 % faster); the
// perturbation follows the coordinates (predicates/sos.hpp), so the output does not depend on
// the order of the input. A point with copies is represented by its first index.
inline Result digital_distinct_hull(Exec& ex, const double* pts, std::int64_t m,
                                    const mesh::Bounds<3>& box, std::int64_t grid, Hull3dStats& st,
                                    std::int64_t n_input);  // (digital/impl/digital.inl)

inline Result hull_core(Exec& ex, const double* in, std::int64_t n, const Hull3dOptions& opt,
                        Hull3dStats& st) {
  auto t0 = Clock::now();
  const mesh::Bounds<3> box = mesh::bounds<3>(ex, in, n);
  if (box.bad) throw_bad(box.bad);
  mesh::SortedPoints<Exec> S = mesh::sort_distinct<3>(ex, in, n, box);
  st.duplicates = S.duplicates;
  ex.sync();
  st.phase_ms.emplace_back("sort", ms_since(t0));
  Result R = opt.method == Method::Digital
                 ? digital_distinct_hull(ex, S.pts.data(), S.m, box, opt.grid, st, n)
                 : distinct_hull(ex, S.pts.data(), S.m, st, n);
  // Back to input indices: the facets' corners, and the vertices in increasing input order.
  t0 = Clock::now();
  const std::int32_t* orig = S.orig.data();
  std::int32_t* t = R.facets.simplices.data();
  ex.for_each_index(
      3 * R.facets.count, GG_LAMBDA(std::int64_t i) { t[i] = orig[t[i]]; });
  auto mark = ex.template alloc<std::int8_t>(std::size_t(n));
  std::int8_t* mk = mark.data();
  ex.fill(mk, n, std::int8_t(0));
  const std::int32_t* v = R.vertices.data();
  ex.for_each_index(
      R.num_vertices, GG_LAMBDA(std::int64_t j) { mk[orig[v[j]]] = 1; });
  auto verts = ex.template alloc<std::int32_t>(std::size_t(R.num_vertices));
  const std::int64_t nv = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return mk[i] != 0; }, verts.data());
  if (nv != R.num_vertices)
    throw Error(ErrorCode::Internal, "convex hull: a vertex was lost mapping back to the input");
  R.vertices = std::move(verts);
  ex.sync();
  st.phase_ms.emplace_back("input_indices", ms_since(t0));
  return R;
}

// A facet's plane as Qhull's / SciPy's `equations` give it: the unit outward normal and the
// offset. Every operation is rounded as written (no fused multiply-add), so both executors
// agree bit for bit with each other and with the host's long-double fallback's neighbours. A
// facet whose rounded normal is zero or not finite (coordinates of very different magnitudes)
// gets NaN and is counted; the host redoes those in long double.
struct PlaneOf {
  const double* p;
  const std::int32_t* t;
  double* eq;
  std::int64_t* redo;
  GG_HD void operator()(std::int64_t f) const {
    using pred::add_rn;
    using pred::mul_rn;
    using pred::sub_rn;
    const double *a = p + 3 * std::int64_t(t[3 * f]), *b = p + 3 * std::int64_t(t[3 * f + 1]),
                 *c = p + 3 * std::int64_t(t[3 * f + 2]);
    double u[3], v[3];
    for (int d = 0; d < 3; ++d) u[d] = sub_rn(b[d], a[d]), v[d] = sub_rn(c[d], a[d]);
    const double n0 = sub_rn(mul_rn(u[1], v[2]), mul_rn(u[2], v[1])),
                 n1 = sub_rn(mul_rn(u[2], v[0]), mul_rn(u[0], v[2])),
                 n2 = sub_rn(mul_rn(u[0], v[1]), mul_rn(u[1], v[0]));
    const double len = sqrt(add_rn(add_rn(mul_rn(n0, n0), mul_rn(n1, n1)), mul_rn(n2, n2)));
    double* e = eq + 4 * f;
    if (!(len > 0 && len <= std::numeric_limits<double>::max())) {
      e[0] = e[1] = e[2] = e[3] = std::numeric_limits<double>::quiet_NaN();
      atomic_add(redo, std::int64_t(1));
      return;
    }
    e[0] = n0 / len, e[1] = n1 / len, e[2] = n2 / len;
    e[3] = -add_rn(add_rn(mul_rn(e[0], a[0]), mul_rn(e[1], a[1])), mul_rn(e[2], a[2]));
  }
};

// The planes of the facets on the executor; the few whose rounded normal vanished (NaN, counted)
// are redone in long double on the host (redo_planes): in place when the executor's memory is
// the host's, else through host copies of the points, the facets and the planes.
inline void planes(Exec& ex, const double* p, std::int64_t n, const std::int32_t* tri,
                   std::int64_t nf, double* eq) {
  auto redo = ex.template alloc<std::int64_t>(1);
  ex.fill(redo.data(), 1, std::int64_t(0));
  ex.for_each_index(nf, PlaneOf{p, tri, eq, redo.data()});
  std::int64_t nredo = 0;
  ex.to_host(redo.data(), 1, &nredo);
  if (!nredo) return;
  if constexpr (Exec::backend == Backend::Cpu) {
    redo_planes(p, tri, nf, eq);
  } else {
    HostVector<double> hp, he;
    HostVector<std::int32_t> ht;
    hp.resize(std::size_t(3 * n));
    he.resize(std::size_t(4 * nf));
    ht.resize(std::size_t(3 * nf));
    ex.to_host(p, 3 * n, hp.data());
    ex.to_host(tri, 3 * nf, ht.data());
    ex.to_host(eq, 4 * nf, he.data());
    redo_planes(hp.data(), ht.data(), nf, he.data());
    ex.from_host(he.data(), 4 * nf, eq);
  }
}

// The outputs' lengths, checked against the caller's arrays before any is written.
inline void check_into(const Hull3dBuffers& into, const Result& R) {
  deliver::check(into.triangles, 3 * R.facets.count, "triangles");
  deliver::check(into.neighbors, 3 * R.facets.count, "neighbors");
  deliver::check(into.vertices, R.num_vertices, "vertices");
  deliver::check(into.equations, 4 * R.facets.count, "equations");
}

// The device memory a hull certainly needs per point (docs/performance.md: 90 B measured on a
// ball of 10^7, 84 B at most on 10^9 since it ran in 80 GB).
constexpr double kLeastBytesPerPoint = 48;

// Host points in, host arrays (the caller's or the result's) out.
inline void compute_impl(const double* xyz, std::int64_t n, const Hull3dOptions& opt, Output& out,
                         Hull3dStats& st) {
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  // (at least the points, their sort keys and the live lists: 90 B a point measured on a ball)
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint, "a convex hull", "points");
  const double* p = xyz;
  typename Exec::template Buffer<double> dev;
  if constexpr (Exec::backend == Backend::Cuda) {
    auto t0 = Clock::now();
    dev = ex.template alloc<double>(std::size_t(3 * n));
    ex.from_host(xyz, 3 * n, dev.data());
    p = dev.data();
    ex.sync();
    st.phase_ms.emplace_back("upload", ms_since(t0));
  }
  Result R = hull_core(ex, p, n, opt, st);
  check_into(opt.into, R);
  auto t0 = Clock::now();
  const std::int64_t nf = R.facets.count;
  auto eq = ex.template alloc<double>(std::size_t(4 * nf));
  planes(ex, p, n, R.facets.simplices.data(), nf, eq.data());
  st.phase_ms.emplace_back("planes", ms_since(t0));
  t0 = Clock::now();
  const Hull3dBuffers& into = opt.into;
  out.num_facets = nf;
  out.num_vertices = R.num_vertices;
  deliver::to_host(ex, R.facets.simplices.data(), 3 * nf, into.triangles, out.triangles);
  deliver::to_host(ex, R.facets.neighbors.data(), 3 * nf, into.neighbors, out.neighbors);
  deliver::to_host(ex, R.vertices.data(), R.num_vertices, into.vertices, out.vertices);
  deliver::to_host(ex, eq.data(), 4 * nf, into.equations, out.equations);
  if constexpr (Exec::backend == Backend::Cuda) st.phase_ms.emplace_back("copy_back", ms_since(t0));
}

// Points in executor memory, result left there (or in the caller's arrays of that memory).
inline void compute_device_impl(const double* xyz, std::int64_t n, const Hull3dOptions& opt,
                                DeviceOutput& out, Hull3dStats& st,
                                const ::gpugeom::detail::ExecContext* outer) {
  Exec ex(opt, outer);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint - 24, "a convex hull",
                                           "points");  // (the points are there already)
  Result R = hull_core(ex, xyz, n, opt, st);
  check_into(opt.into, R);
  const auto t0 = Clock::now();
  const std::int64_t nf = R.facets.count;
  auto eq = ex.template alloc<double>(std::size_t(4 * nf));
  planes(ex, xyz, n, R.facets.simplices.data(), nf, eq.data());
  const Hull3dBuffers& into = opt.into;
  auto tri = deliver::place(ex, R.facets.simplices, 3 * nf, into.triangles);
  auto nb = deliver::place(ex, R.facets.neighbors, 3 * nf, into.neighbors);
  auto vx = deliver::place(ex, R.vertices, R.num_vertices, into.vertices);
  auto pl = deliver::place(ex, eq, 4 * nf, into.equations);
  ex.sync();  // the caller may read them now (and free them on any stream)
  st.phase_ms.emplace_back("planes", ms_since(t0));
  out.num_facets = nf;
  out.num_vertices = R.num_vertices;
  out.triangles = tri.own();
  out.neighbors = nb.own();
  out.vertices = vx.own();
  out.equations = pl.own();
}
