// 3D Delaunay's pipeline (thesis 5.3.1) around phase 1 (triangulator.inl) and phase 2
// (repair.inl): the points prepared, the failed faces repaired, the flat tetrahedra dropped,
// the output delivered to the caller's memory; the backend's host and device entries.

// What both methods start from: the distinct points in curve order (the order of their
// indices; the perturbation follows coordinates, predicates/sos.hpp), their box and the first
// tetrahedron (its centroid is the kernel point).
struct Prepared {
  mesh::SortedPoints<Exec> S;
  mesh::Bounds<3> box;
  mesh::Tetra first;
};
inline Prepared prepare_points(Exec& ex, const double* in, std::int64_t n, bool on_device,
                               Delaunay3dStats& st) {
  const auto t0 = Clock::now();
  auto raw = ex.template alloc<double>(std::size_t(3 * n));
  if (on_device)
    ex.copy(in, 3 * n, raw.data());
  else
    ex.from_host(in, 3 * n, raw.data());
  const mesh::Bounds<3> box = mesh::bounds_in_place<3>(ex, raw.data(), n);
  if (box.bad) mesh::throw_bad_coordinates(box.bad);
  mesh::SortedPoints<Exec> S = mesh::sort_distinct<3>(ex, raw.data(), n, box);
  raw = typename Exec::template Buffer<double>();
  st.points = n;
  st.distinct_points = S.m;
  st.duplicates = S.duplicates;
  if (S.m < 4)
    throw Error(ErrorCode::DegenerateInput,
                "fewer than 4 distinct points (" + std::to_string(S.m) +
                    "): a 3D Delaunay triangulation needs 4 points not on one plane");
  const mesh::Tetra first =
      mesh::first_tetrahedron(ex, S.pts.data(), S.m, n, "a 3D Delaunay triangulation", true);
  ex.sync();
  st.phase_ms.push_back({"prepare", ms_since(t0)});
  return Prepared{std::move(S), box, first};
}

// After phase 1: every face tested, and phase 2 (repair.inl) where some are not locally
// Delaunay. The store is then the Delaunay tetrahedralisation of the perturbed points, flat
// tetrahedra included; returns how many of those it holds. Counters and phases into st.
// only: as find_failed's.
inline std::int64_t repair_phase(Exec& ex, Triangulator& T, std::int64_t m,
                                 const ProgressFn& progress, Delaunay3dStats& st,
                                 const std::int8_t* only = nullptr) {
  auto t0 = Clock::now();
  if (T.cavities_) return -1;  // (Bowyer-Watson leaves no face to repair; flats not counted)
  auto failed = ex.template alloc<std::int8_t>(std::size_t(m + 1));
  std::int64_t nflat = 0;
  const std::int64_t nfailed = T.find_failed(failed, nflat, only);
  st.phase_ms.push_back({"find_failed", ms_since(t0)});
  t0 = Clock::now();
  RepairCount rc;
  if (nfailed > 0) {
    if (progress) progress(Delaunay3dProgress{"splay", m, m, 0});
    const std::int64_t used = repair_tets(
        ex, T.g_, T.tet_.data(), T.counters().used, failed.data(),
        [&T](std::int64_t slots) { return T.store_for(slots); }, rc);
    T.set_used(used);
  }
  st.phase_ms.push_back({"splay", ms_since(t0)});
  st.failed_vertices = rc.failed_vertices;
  st.stars_built = rc.stars_built;
  st.stars_changed = rc.stars_changed;
  st.star_insertions = rc.insertions;
  st.splay_rounds = rc.rounds;
  st.splay_removed = rc.removed;
  st.splay_added = rc.added;
  st.us_splay_build = std::int64_t(1000 * rc.build_ms);
  st.us_splay_rounds = std::int64_t(1000 * rc.splay_ms);
  st.us_splay_patch = std::int64_t(1000 * rc.patch_ms);
  st.us_splay_check = std::int64_t(1000 * rc.check_ms);
  st.us_splay_take = std::int64_t(1000 * rc.take_ms);
  return nflat;
}

// The whole pipeline on the executor: prepare, phase 1, phase 2 where phase 1 left failed
// faces, the flat tetrahedra left out, then the finite tetrahedra in input indices (f) with S's
// duplicate map.
template <class Body, class Into = mesh::OwnArrays>
inline void triangulate_core(Exec& ex, const double* in, std::int64_t n, bool on_device,
                             const Delaunay3dOptions& opt, Delaunay3dStats& st, Body body,
                             Into into = {}) {
  const std::int64_t max_rounds = ex.tuning().del3d.max_flip_rounds;
  const ProgressFn& progress = opt.progress;
  Prepared P = prepare_points(ex, in, n, on_device, st);
  mesh::SortedPoints<Exec>& S = P.S;
  const mesh::Bounds<3>& box = P.box;
  const mesh::Tetra& first = P.first;
  auto t0 = Clock::now();
  if (opt.method == Method::Digital) {  // DigiDel3D (digital/impl/pipeline.inl)
    auto f = digital_tets(ex, S, box, first, opt.grid, progress, st);
    if (f) {
      t0 = Clock::now();
      body(S, *f);
      st.phase_ms.push_back({"output", ms_since(t0)});
      return;
    }
    // (stars too large to splay here: the incremental method, counter digital_fallback)
  }
  t0 = Clock::now();
  Triangulator T(ex, S.pts.data(), std::int32_t(S.m), first, max_rounds, progress, st,
                 Triangulator::cavities_for(ex));
  T.run();
  st.phase_ms.push_back({"insert_flip", ms_since(t0)});
  std::int64_t nflat = repair_phase(ex, T, S.m, progress, st);
  t0 = Clock::now();
  std::int64_t flats = 0;
  if (nflat < 0 && flats_next_to_outside(ex, T.g_, T.tet_.data(), T.counters().used) == 0)
    nflat = 0;  // (the cavities count none as they go: the outside tells whether there are any)
  if (nflat != 0) flats = drop_flats(ex, T.g_, T.tet_.data(), T.counters().used);
  st.flat_tetrahedra = flats;
  st.phase_ms.push_back({"drop_flats", ms_since(t0)});
  t0 = Clock::now();
  if (progress) progress(Delaunay3dProgress{"output", S.m, S.m, 0});
  auto f = T.finish(S.orig.data(), into);
  st.phase_ms.push_back({"output.compact", ms_since(t0)});
  T.report();
  body(S, f);
  st.phase_ms.push_back({"output", ms_since(t0)});
}

// What the output holds beyond the tetrahedra, made on the executor: the vertex map (the last
// tetrahedron of each vertex, copies taking their original's) and the hull facets (faces with no
// neighbour, outward, in tetrahedron order).
struct Extras {
  typename Exec::template Buffer<std::int32_t> vertex_to_simplex, hull_facets;
  std::int64_t num_hull_facets = 0;
};
// dup: the duplicate map (n entries), or null where there is no duplicate. orig: where the
// compaction made each curve position's last tetrahedron (f.last; finish()), the input index of
// each of the m positions, else null.
inline Extras extras(Exec& ex, const std::int32_t* dup, mesh::Compacted<Exec>& f, std::int64_t n,
                     const std::int32_t* orig = nullptr, std::int64_t m = 0) {
  Extras E;
  E.vertex_to_simplex = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* v = E.vertex_to_simplex.data();
  const std::int32_t* tv = f.simplices_data();
  const std::int32_t* nb = f.neighbors_data();
  ex.fill(v, n, std::int32_t(-1));
  if (orig && f.last.data()) {
    const std::int32_t* last = f.last.data();
    ex.for_each_index(
        m, GG_LAMBDA(std::int64_t w) { v[orig[w]] = last[w]; });
  } else {
    // (from the last tetrahedron down: a vertex's first entry seen is then mostly its largest,
    // and the later ones see it with a plain read; upwards every entry was an atomic: 27 a vertex)
    const std::int64_t entries = 4 * f.count;
    ex.for_each_index(
        entries, GG_LAMBDA(std::int64_t i) {
          const std::int64_t e = entries - 1 - i;
          atomic_max(v + tv[e], std::int32_t(e / 4));
        });
  }
  if (dup) {
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          if (dup[i] >= 0) v[i] = v[dup[i]];
        });
  }
  // The hull facets, found per tetrahedron rather than per face: the 4 * count faces pass 2^31
  // from about 8·10^7 points, beyond the int32 positions compact_indices writes (10^8 uniform
  // points read outside the neighbours there, an illegal address on the H200). The tetrahedra
  // with a face on the hull are counted first, so the lists are as long as the hull, not as the
  // output (the per-face list was 16 bytes a tetrahedron, 10.8 GB at 10^8 points).
  auto on_hull = GG_LAMBDA(std::int64_t t)->int {
    return int(nb[4 * t] < 0) + int(nb[4 * t + 1] < 0) + int(nb[4 * t + 2] < 0) +
           int(nb[4 * t + 3] < 0);
  };
  auto cnt = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      f.count, GG_LAMBDA(std::int64_t t)->std::int64_t { return on_hull(t) > 0 ? 1 : 0; },
      std::int64_t(0), thrust::plus<std::int64_t>(), cnt.data());
  std::int64_t nt = 0;
  ex.to_host(cnt.data(), 1, &nt);
  auto ht = ex.template alloc<std::int32_t>(std::size_t(nt + 1));
  std::int32_t* a = ht.data();
  ex.compact_indices(
      f.count, GG_LAMBDA(std::int64_t t) { return on_hull(t) > 0; }, a);
  auto off = ex.template alloc<std::int32_t>(std::size_t(nt + 1));
  std::int32_t* o = off.data();
  ex.exclusive_scan_of(
      nt + 1, GG_LAMBDA(std::int64_t j)->std::int32_t { return j < nt ? on_hull(a[j]) : 0; }, o);
  std::int32_t nh32 = 0;
  ex.to_host(o + nt, 1, &nh32);
  const std::int64_t nh = nh32;
  E.num_hull_facets = nh;
  E.hull_facets = ex.template alloc<std::int32_t>(std::size_t(3 * nh + 1));
  std::int32_t* h = E.hull_facets.data();
  ex.for_each_index(
      nt, GG_LAMBDA(std::int64_t j) {
        const std::int64_t t = a[j];
        std::int64_t at = o[j];
        for (int k = 0; k < 4; ++k) {
          if (nb[4 * t + k] >= 0) continue;
          for (int i = 0; i < 3; ++i) h[3 * at + i] = tv[4 * t + face_vertex(k, i)];
          ++at;
        }
      });
  return E;
}

// The outputs' lengths, checked against the caller's arrays before any is written.
inline void check_into(const Triangulation3dBuffers& into, std::int64_t count, std::int64_t nh,
                       std::int64_t n) {
  deliver::check(into.tetrahedra, 4 * count, "tetrahedra");
  deliver::check(into.neighbors, 4 * count, "neighbors");
  deliver::check(into.duplicate_of, n, "duplicate_of");
  deliver::check(into.vertex_to_simplex, n, "vertex_to_simplex");
  deliver::check(into.hull_facets, 3 * nh, "hull_facets");
}

// The tetrahedra and neighbours straight into the result's arrays where that may be
// (mesh::IntoResult).
inline auto host_arrays(const Triangulation3dBuffers& into, Output& out) {
  return mesh::IntoResult<4, Exec, decltype(out.tetrahedra)>{
      bool(into.tetrahedra) || bool(into.neighbors), out.tetrahedra, out.neighbors};
}

// The finished tetrahedralisation to host arrays: the caller's (into) or the result's.
inline void to_output(Exec& ex, mesh::SortedPoints<Exec>& S, mesh::Compacted<Exec>& f,
                      std::int64_t n, const Triangulation3dBuffers& into, Output& out) {
  Extras E = extras(ex, S.duplicates ? S.dup.data() : nullptr, f, n, S.orig.data(), S.m);
  check_into(into, f.count, E.num_hull_facets, n);
  out.num_duplicates = S.duplicates;
  out.num_tetrahedra = f.count;
  out.num_hull_facets = E.num_hull_facets;
  if (!f.placed_simplices) {  // (else in out's arrays already: host_arrays)
    deliver::to_host(ex, f.simplices.data(), 4 * f.count, into.tetrahedra, out.tetrahedra);
    deliver::to_host(ex, f.neighbors.data(), 4 * f.count, into.neighbors, out.neighbors);
  }
  if (S.duplicates)
    deliver::to_host(ex, S.dup.data(), n, into.duplicate_of, out.duplicate_of);
  else
    deliver::fill_host(ex, n, std::int32_t(-1), into.duplicate_of, out.duplicate_of);
  deliver::to_host(ex, E.vertex_to_simplex.data(), n, into.vertex_to_simplex,
                   out.vertex_to_simplex);
  deliver::to_host(ex, E.hull_facets.data(), 3 * E.num_hull_facets, into.hull_facets,
                   out.hull_facets);
}

// ... left in executor memory: the caller's arrays (into) or the library's, handed over.
inline void to_device_output(Exec& ex, mesh::SortedPoints<Exec>& S, mesh::Compacted<Exec>& f,
                             std::int64_t n, const Triangulation3dBuffers& into,
                             DeviceOutput& out) {
  Extras E = extras(ex, S.duplicates ? S.dup.data() : nullptr, f, n, S.orig.data(), S.m);
  const std::int64_t nh = E.num_hull_facets;
  check_into(into, f.count, nh, n);
  if (!S.duplicates && !into.duplicate_of)  // no duplicates: the map is all -1
    S.dup = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* dup = S.dup.size() ? S.dup.data() : into.duplicate_of.data;
  if (!S.duplicates) ex.fill(dup, n, std::int32_t(-1));
  auto te = deliver::place(ex, f.simplices, 4 * f.count, into.tetrahedra);
  auto nb = deliver::place(ex, f.neighbors, 4 * f.count, into.neighbors);
  auto dp = deliver::place(ex, S.dup, S.dup.size() ? n : 0, into.duplicate_of);
  auto vs = deliver::place(ex, E.vertex_to_simplex, n, into.vertex_to_simplex);
  auto hf = deliver::place(ex, E.hull_facets, 3 * nh, into.hull_facets);
  ex.sync();  // the caller may read them now (and free them on any stream)
  out.num_tetrahedra = f.count;
  out.num_duplicates = S.duplicates;
  out.num_hull_facets = nh;
  out.tetrahedra = te.own();
  out.neighbors = nb.own();
  out.duplicate_of = dp.own();
  out.vertex_to_simplex = vs.own();
  out.hull_facets = hf.own();
}

// The device memory a tetrahedralisation certainly needs per point: phase 1's store alone
// (7 slots a point at the least, 52 bytes each with the keys, history and split ranks) and the
// points (docs/performance.md has the measured peaks).
constexpr double kLeastBytesPerPoint = 7 * 52 + 40;

inline void triangulate_impl(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                             Output& out, Delaunay3dStats& st) {
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint,
                                           "a 3D Delaunay tetrahedralisation", "points");
  triangulate_core(
      ex, xyz, n, false, opt, st,
      [&](mesh::SortedPoints<Exec>& S, typename Triangulator::Finished& f) {
        to_output(ex, S, f, n, opt.into, out);
      },
      host_arrays(opt.into, out));
}

inline void triangulate_device_impl(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                                    DeviceOutput& out, Delaunay3dStats& st,
                                    const ::gpugeom::detail::ExecContext* outer) {
  Exec ex(opt, outer);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint - 24,
                                           "a 3D Delaunay tetrahedralisation", "points");
  triangulate_core(ex, xyz, n, true, opt, st,
                   [&](mesh::SortedPoints<Exec>& S, typename Triangulator::Finished& f) {
                     to_device_output(ex, S, f, n, opt.into, out);
                   });
}
