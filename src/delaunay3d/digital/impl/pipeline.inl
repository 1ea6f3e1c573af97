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

// The stars of phase 2 and what they need (the geometry, its exact scratch, the counters).
struct DigitalStars {
  Geo g;
  LeasePool<Exec> pool;
  typename Exec::template Buffer<digital3d_impl::StarCounters> ctr;
  StarStore T;
};

// Phases 1 and 2: the diagram, the working sets and every point's first star. Returns false,
// building nothing, where many points lie on the box's planes (the incremental method then).
inline bool digital_stars(Exec& ex, mesh::SortedPoints<Exec>& S, const mesh::Bounds<3>& box,
                          const mesh::Tetra& first, std::int64_t grid, Delaunay3dStats& st,
                          DigitalStars& D) {
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
    st.digital_points_on_box = on_box;
    if (on_box > std::max<std::int64_t>(4096, m / 100)) {
      st.digital_fallback = 1;
      phase("digital_box_planes");
      return false;
    }
  }
  std::int64_t side = grid > 0 ? grid : digital_side(m);
  point_voronoi_impl::CellFrame F = digital_frame(box, side);
  PointVoronoi V = map_point_sites(ex, S.pts.data(), m, F);
  // The automatic side looks at the occupancy too: where more than a tenth of the points share
  // a cell (clustered input, points on surfaces), a point without a cell of its own starts from
  // its cell's site's set and costs insertions later, so the side doubles once, up to
  // kFinestCells cells (the diagram's memory) and 1024.
  constexpr double kFinestCells = double(1 << 28);
  if (grid == 0 && V.nmiss > m / 10) {
    const double cells = double(F.n[0]) * double(F.n[1]) * double(F.n[2]);
    const double grow = std::min(2.0, std::cbrt(kFinestCells / cells));
    const std::int64_t finer = std::min<std::int64_t>(1024, std::int64_t(double(side) * grow));
    if (finer > side) {
      side = finer;
      F = digital_frame(box, side);
      V = map_point_sites(ex, S.pts.data(), m, F);
      st.digital_grid_refined = 1;
    }
  }
  phase("digital_grid");
  colour_cells(ex, m, F, V);
  phase("digital_pba");
  st.digital_grid = side;
  st.sites = V.nsites;
  st.sketch_missing = V.nmiss;
  WorkingSets W = working_sets(ex, m, F, V);
  V = PointVoronoi();
  st.digital_working_pairs = W.pairs;
  st.digital_working_set_points = W.total;
  st.digital_working_sets_augmented = W.augmented;
  phase("digital_working_sets");
  D.g.p = S.pts.data();
  for (int k = 0; k < 3; ++k) D.g.s[k] = first.s[k];
  D.g.m = std::int32_t(m);
  D.pool = LeasePool<Exec>(
      ex, std::clamp<std::int64_t>(std::min<std::int64_t>(ex.concurrency(), m / 8), 64, 1024),
      pred::kInsphereScratch);
  D.g.lease = D.pool.view;
  D.ctr = ex.template alloc<digital3d_impl::StarCounters>(1);
  D.T = create_stars(ex, D.g, m, W.start.data(), W.size.data(), W.pts.data(), D.ctr);
  st.digital_star_slots_created = D.T.slots;
  phase("digital_stars");
  return true;
}

// Phase 3 on the stars: splaying; false where a star grew too large (kHugeStar).
// (vertex_rounds, first_requests: see splay_stars)
inline bool digital_splay(Exec& ex, DigitalStars& D, Delaunay3dStats& st, bool vertex_rounds = true,
                          std::int64_t first_requests = 0) {
  const auto t0 = Clock::now();
  const SplayCount sc = splay_stars(ex, D.g, D.T, D.ctr, vertex_rounds, first_requests);
  st.digital_fallback = sc.gave_up ? 1 : 0;
  st.digital_splay_rounds = sc.rounds;
  st.digital_splay_vertex_rounds = sc.vertex_rounds;
  st.digital_star_insertions = sc.insertions;
  st.digital_star_requests = sc.requests;
  st.digital_splay_request_spills = sc.spills;
  st.digital_star_growths = D.T.growths;
  st.digital_star_slots = D.T.slots;
  ex.sync();
  st.phase_ms.push_back({"digital_splay", ms_since(t0)});
  // (the splay's parts, within digital_splay: the checks, the requests' sort, the takes)
  st.phase_ms.push_back({"digital_splay.check", sc.check_ms});
  st.phase_ms.push_back({"digital_splay.sort", sc.sort_ms});
  st.phase_ms.push_back({"digital_splay.take", sc.take_ms});
  return !sc.gave_up;
}

// The whole method. Returns no result where it fell back (see above): the caller then runs
// the incremental method.
inline std::optional<mesh::Compacted<Exec>> digital_tets(
    Exec& ex, mesh::SortedPoints<Exec>& S, const mesh::Bounds<3>& box, const mesh::Tetra& first,
    std::int64_t grid, const ProgressFn& progress, Delaunay3dStats& st) {
  const std::int64_t m = S.m;
  DigitalStars D;
  if (!digital_stars(ex, S, box, first, grid, st, D)) return std::nullopt;
  if (progress) progress(Delaunay3dProgress{"splay", m, m, 0});
  if (!digital_splay(ex, D, st)) return std::nullopt;
  if (progress) progress(Delaunay3dProgress{"output", m, m, 0});
  const auto t0 = Clock::now();
  std::int64_t flats = 0;
  mesh::Compacted<Exec> f = star_tets(ex, D.g, D.T, S.orig.data(), flats);
  st.flat_tetrahedra = flats;
  ex.sync();
  st.phase_ms.push_back({"digital_tetrahedra", ms_since(t0)});
  return f;
}
