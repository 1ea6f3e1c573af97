// The digital method's whole pipeline on an executor (digital.hpp), included inside
// gpugeom::del2d::{cpu,cuda}_impl after triangulate.inl, sketch.inl and shift.inl. The points go
// to the executor once; the sketch, the start and the Triangulator's records are built there
// from one another; only counts, the sketch's boundary (the hull fill) and the start's boundary
// (its check) come to the host until the result does.

inline void triangulate_digital_impl(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                                     Output& out, Stats& st) {
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
  st.counters["points"] = n;
  st.counters["distinct_points"] = P.m;
  st.counters["duplicates"] = P.duplicates;
  ex.sync();
  st.phase_ms.push_back({"prepare", ms_since(t0)});
  auto deliver = [&](typename Triangulator::Finished& f) {
    deliver_host_results(ex, opt.into, n, P, f, out, st, pf);
  };
  // Where the sketch cannot be used: the incremental method on the same preparation.
  auto incremental = [&] {
    st.counters["digital_fallback"] = 1;
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
  st.counters["grid_width"] = s.width;
  st.counters["grid_height"] = s.height;
  if (!s.exact) return incremental();
  HeldStart S;
  {
    HeldSketch H = sketch_on(ex, pts.data(), n, s);
    for (const auto& [name, ms] : s.phase_ms) st.phase_ms.push_back({"digital_" + name, ms});
    st.counters["sites"] = n - H.nmiss;
    st.counters["sketch_missing"] = H.nmiss;
    st.counters["debris_pixels"] = s.debris;
    st.counters["debris_candidates"] = s.debris_candidates;
    st.counters["pinched_corners"] = s.pinched;
    st.counters["hull_triangles"] = s.hull_triangles;
    st.counters["sketch_not_disk"] = s.not_disk;
    if (H.nt == 0) return incremental();
    digital::Start start;
    S = shift_on(ex, pts.data(), n, s, H, start);
    for (const auto& [name, ms] : start.phase_ms) st.phase_ms.push_back({"digital_" + name, ms});
    st.counters["shifted"] = start.shifted;
    st.counters["bad_inner"] = start.bad_inner;
    st.counters["bad_boundary"] = start.bad_boundary;
    st.counters["shift_rounds"] = start.shift_rounds;
    st.counters["delete_rounds"] = start.delete_rounds;
    st.counters["start_vertices"] = start.vertices;
    st.counters["start_triangles"] = start.triangle_count;
    if (!start.valid) return incremental();
  }  // (the grid's and the sketch's memory back before the Triangulator's)
  st.counters["digital_fallback"] = 0;
  pts = {};
  auto f =
      run_from_start(ex, P, n, S.tri.data(), S.nt, S.twin.data(), S.hint.data(), opt.profile, st);
  deliver(f);
}
