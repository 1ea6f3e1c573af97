// The digital method's whole pipeline on an executor (digital.hpp), included inside
// gpugeom::del2d::{cpu,cuda}_impl after triangulate.inl, sketch.inl and shift.inl. The points go
// to the executor once; the sketch, the start and the Triangulator's records are built there
// from one another; only counts, the sketch's boundary (the hull fill) and the start's boundary
// (its check) come to the host until the result does.

inline void triangulate_digital_impl(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                                     Output& out, Delaunay2dStats& st) {
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint,
                                           "a 2D Delaunay triangulation", "points");
  auto t0 = std::chrono::steady_clock::now();
  auto pts = ex.template alloc<double>(std::size_t(2 * n));
  ex.from_host(xy, 2 * n, pts.data());
  // The incremental method's preparation (its checks and errors, the Hilbert order, the
  // duplicates), on the points already there; its box frames the grid.
  Prepared P = prepare(ex, pts.data(), n, true);
  detail::Prefault pf;
  size_host_results(opt.into, n, P, out, pf);
  st.points = n;
  st.distinct_points = P.m;
  st.duplicates = P.duplicates;
  ex.sync();
  st.phase_ms.push_back({"prepare", ms_since(t0)});
  auto deliver = [&](typename Triangulator::Finished& f) {
    deliver_host_results(ex, opt.into, n, P, f, out, st, pf);
  };
  // Where the sketch cannot be used: the incremental method on the same preparation.
  auto incremental = [&] {
    st.digital_fallback = 1;
    Triangulator T(ex, P, st, opt.profile);
    T.run();
    const auto t1 = std::chrono::steady_clock::now();
    T.report();
    T.release_work();
    auto f = T.finish();
    st.phase_ms.push_back({"finish", ms_since(t1)});
    deliver(f);
  };
  digital::Sketch s;
  const std::int64_t side = opt.grid ? opt.grid : digital::auto_side(P.box.lo, P.box.hi, n);
  digital::set_frame(s, P.box.lo, P.box.hi, side);
  st.grid_width = s.width;
  st.grid_height = s.height;
  if (!s.exact) return incremental();
  HeldStart S;
  {
    HeldSketch H = sketch_on(ex, pts.data(), n, s);
    for (const auto& [name, ms] : s.phase_ms) st.phase_ms.push_back({"digital_" + name, ms});
    st.sites = n - H.nmiss;
    st.sketch_missing = H.nmiss;
    st.debris_pixels = s.debris;
    st.debris_candidates = s.debris_candidates;
    st.pinched_corners = s.pinched;
    st.hull_triangles = s.hull_triangles;
    st.sketch_not_disk = s.not_disk;
    if (H.nt == 0) return incremental();
    digital::Start start;
    S = shift_on(ex, pts.data(), n, s, H, start);
    for (const auto& [name, ms] : start.phase_ms) st.phase_ms.push_back({"digital_" + name, ms});
    st.shifted = start.shifted;
    st.bad_inner = start.bad_inner;
    st.bad_boundary = start.bad_boundary;
    st.shift_rounds = start.shift_rounds;
    st.delete_rounds = start.delete_rounds;
    st.start_vertices = start.vertices;
    st.start_triangles = start.triangle_count;
    if (!start.valid) return incremental();
  }  // (the grid's and the sketch's memory back before the Triangulator's)
  st.digital_fallback = 0;
  pts = {};
  auto f =
      run_from_start(ex, P, n, S.tri.data(), S.nt, S.twin.data(), S.hint.data(), opt.profile, st);
  deliver(f);
}
