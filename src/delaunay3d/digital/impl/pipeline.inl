// DigiDel3D (thesis 4.5.2) on one executor: the digital Voronoi diagram and working sets
// (working_sets.inl), a convex star per point and star splaying (stars.inl), then the
// tetrahedra in the incremental method's output form. Included inside an executor's namespace
// after those files; triangulate.inl calls it after the shared preparation (the same distinct
// points in the same curve order and the same kernel point, so the same perturbation and the
// same tetrahedra).

// The grid side chosen from the point count: about 32 cells a point.
inline std::int64_t digital_side(std::int64_t m) {
  return std::clamp<std::int64_t>(std::int64_t(std::llround(std::cbrt(32.0 * double(m)))), 16,
                                  1024);
}

// Returns no result where the stars grew too large to splay on the executor (stars.inl,
// kHugeStar): the caller then runs the incremental method.
inline std::optional<mesh::Compacted<Exec>> digital_tets(Exec& ex, mesh::SortedPoints<Exec>& S,
                                                         const mesh::Bounds<3>& box,
                                                         const mesh::Tetra& first,
                                                         std::int64_t grid,
                                                         const ProgressFn& progress, Stats& st) {
  auto t0 = Clock::now();
  auto phase = [&](const char* name) {
    ex.sync();
    st.phase_ms.push_back({name, ms_since(t0)});
    t0 = Clock::now();
  };
  const std::int64_t m = S.m;
  {
    // Many points on the planes of the box (the hull planes of integer grids, of boxes) give
    // stars too large to splay here (stars.inl, kHugeStar): the incremental method at once,
    // rather than after rounds of growing them. (Other planes are left to kHugeStar.)
    const double* p = S.pts.data();
    auto cnt = ex.template alloc<std::int64_t>(1);
    const mesh::Bounds<3> b = box;
    ex.transform_reduce_into(
        m,
        GG_LAMBDA(std::int64_t i)->std::int64_t {
          for (int a = 0; a < 3; ++a)
            if (p[3 * i + a] == b.lo[a] || p[3 * i + a] == b.hi[a]) return 1;
          return 0;
        },
        std::int64_t(0), thrust::plus<std::int64_t>(), cnt.data());
    std::int64_t on_box = 0;
    ex.to_host(cnt.data(), 1, &on_box);
    st.counters["digital_points_on_box"] = on_box;
    if (on_box > std::max<std::int64_t>(4096, m / 100)) {
      st.counters["digital_fallback"] = 1;
      phase("digital_box_planes");
      return std::nullopt;
    }
  }
  const std::int64_t side = grid > 0 ? grid : digital_side(m);
  const point_voronoi_impl::CellFrame F = digital_frame(box, side);
  PointVoronoi V = map_point_sites(ex, S.pts.data(), m, F);
  phase("digital_grid");
  colour_cells(ex, m, F, V);
  phase("digital_pba");
  st.counters["digital_grid"] = side;
  st.counters["sites"] = V.nsites;
  st.counters["sketch_missing"] = V.nmiss;
  WorkingSets W = working_sets(ex, m, F, V);
  V = PointVoronoi();
  st.counters["digital_working_pairs"] = W.pairs;
  st.counters["digital_working_set_points"] = W.total;
  st.counters["digital_working_sets_augmented"] = W.augmented;
  phase("digital_working_sets");
  Geo g;
  g.p = S.pts.data();
  for (int k = 0; k < 3; ++k) g.s[k] = first.s[k];
  g.m = std::int32_t(m);
  LeasePool<Exec> pool(
      ex, std::clamp<std::int64_t>(std::min<std::int64_t>(ex.concurrency(), m / 8), 64, 1024),
      pred::kInsphereScratch);
  g.lease = pool.view;
  auto ctr = ex.template alloc<digital3d_impl::StarCounters>(1);
  StarStore T = create_stars(ex, g, m, W.start.data(), W.size.data(), W.pts.data(), ctr);
  W = WorkingSets();
  st.counters["digital_star_slots_created"] = T.slots;
  phase("digital_stars");
  if (progress) progress(Delaunay3dProgress{"splay", m, m, 0});
  const SplayCount sc = splay_stars(ex, g, T, ctr);
  st.counters["digital_fallback"] = sc.gave_up ? 1 : 0;
  st.counters["digital_splay_rounds"] = sc.rounds;
  st.counters["digital_star_insertions"] = sc.insertions;
  st.counters["digital_star_requests"] = sc.requests;
  st.counters["digital_star_growths"] = T.growths;
  st.counters["digital_star_slots"] = T.slots;
  phase("digital_splay");
  if (sc.gave_up) return std::nullopt;
  if (progress) progress(Delaunay3dProgress{"output", m, m, 0});
  std::int64_t flats = 0;
  mesh::Compacted<Exec> f = star_tets(ex, g, T, S.orig.data(), flats);
  st.counters["flat_tetrahedra"] = flats;
  phase("digital_tetrahedra");
  return f;
}
