// 2D Delaunay's pipeline around the Triangulator (triangulator.inl): the points prepared, the
// triangulation run, the output delivered to the caller's memory; the backend's host and device
// entries, and the Triangulator from a given start (the digital method, DynamicDelaunay2d).

// The device memory a triangulation needs per point at least, checked before any launch: the
// rounds' arrays with the flip log at its least (docs/performance.md, H100 80 GB: 167.7 B a
// point measured at 5·10^8; where memory is left the log takes more, up to 236 B a point).
constexpr double kLeastBytesPerPoint = 168;

// The pipeline after the preparation: body(P, f) takes the result (written where into says:
// mesh/compact.hpp).
template <class Body, class Into = mesh::OwnArrays>
inline void triangulate_prepared(Exec& ex, Prepared& P, bool profile, Delaunay2dStats& st,
                                 Body body, bool peel_flats = true, Into into = {}) {
  // The rounds' arrays, checked again now that the points are prepared: where they exceed the
  // driver's free memory, the preparation's freed blocks go back to the driver first
  // (require_memory), so that the largest arrays are not cut from the pool's pieces of them.
  ::gpugeom::detail::require_device_memory(ex, P.m, kLeastBytesPerPoint - 20,
                                           "a 2D Delaunay triangulation", "points");
  Triangulator T(ex, P, st, profile);
  T.run(peel_flats);
  const auto t0 = std::chrono::steady_clock::now();
  T.report();
  T.release_work();
  auto f = T.finish(into);
  body(P, f);
  st.phase_ms.push_back({"output", ms_since(t0)});
}

// The whole pipeline; the result stays on the executor (f) with P's duplicate map.
// before(P) runs once the distinct points are known, before the device work.
template <class Before, class Body, class Into = mesh::OwnArrays>
inline void triangulate_core(Exec& ex, const double* xy, std::int64_t n, bool on_device,
                             bool profile, Delaunay2dStats& st, Before before, Body body,
                             bool peel_flats = true, Into into = {}) {
  auto t0 = std::chrono::steady_clock::now();
  Prepared P = prepare(ex, xy, n, on_device);
  before(P);
  st.points = n;
  st.distinct_points = P.m;
  st.duplicates = P.duplicates;
  ex.sync();
  st.phase_ms.push_back({"prepare", ms_since(t0)});
  st.phase_ms.push_back({"upload", P.upload_ms});  // (part of prepare)
  triangulate_prepared(ex, P, profile, st, body, peel_flats, into);
}

// The three outputs' lengths, checked against the caller's arrays before any is written.
inline void check_into(const Triangulation2dBuffers& into, std::int64_t count, std::int64_t n) {
  deliver::check(into.triangles, 3 * count, "triangles");
  deliver::check(into.neighbors, 3 * count, "neighbors");
  deliver::check(into.duplicate_of, n, "duplicate_of");
}

// The host entries' result arrays. On the GPU the host is idle while the device triangulates:
// they are sized for the most triangles m distinct points can have (2m - 5; cut to the count
// later, keeping the pages) and faulted in meanwhile, so the copy back runs at the transfer's
// rate.
inline void size_host_results(const Triangulation2dBuffers& into, std::int64_t n, const Prepared& P,
                              Output& out, detail::Prefault& pf) {
  if constexpr (Exec::backend == Backend::Cuda) {
    const std::int64_t bound = 3 * delaunay2d_max_triangles(P.m);
    if (!into.triangles) out.triangles.resize(std::size_t(bound));
    if (!into.neighbors) out.neighbors.resize(std::size_t(bound));
    if (!into.duplicate_of) out.duplicate_of.resize(std::size_t(n));
    pf.add(out.triangles.data(), out.triangles.size() * sizeof(std::int32_t));
    pf.add(out.neighbors.data(), out.neighbors.size() * sizeof(std::int32_t));
    pf.add(out.duplicate_of.data(), out.duplicate_of.size() * sizeof(std::int32_t));
    pf.start();
  }
}

inline void deliver_host_results(Exec& ex, const Triangulation2dBuffers& into, std::int64_t n,
                                 Prepared& P, typename Triangulator::Finished& f, Output& out,
                                 Delaunay2dStats& st, detail::Prefault& pf) {
  const auto t0 = std::chrono::steady_clock::now();
  pf.wait();
  st.phase_ms.push_back({"prefault_wait", ms_since(t0)});
  check_into(into, f.count, n);
  out.num_duplicates = P.duplicates;
  out.num_triangles = f.count;
  if (!f.placed_simplices) {  // (else in out's arrays already: mesh::IntoResult)
    deliver::to_host(ex, f.simplices.data(), 3 * f.count, into.triangles, out.triangles);
    deliver::to_host(ex, f.neighbors.data(), 3 * f.count, into.neighbors, out.neighbors);
  }
  if (P.duplicates)
    deliver::to_host(ex, P.dup.data(), n, into.duplicate_of, out.duplicate_of);
  else
    deliver::fill_host(ex, n, std::int32_t(-1), into.duplicate_of, out.duplicate_of);
  st.phase_ms.push_back({"copy_back", ms_since(t0)});
}

inline void triangulate_impl(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                             Output& out, Delaunay2dStats& st) {
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint,
                                           "a 2D Delaunay triangulation", "points");
  detail::Prefault pf;
  triangulate_core(
      ex, xy, n, false, opt.profile, st,
      [&](Prepared& P) { size_host_results(opt.into, n, P, out, pf); },
      [&](Prepared& P, typename Triangulator::Finished& f) {
        deliver_host_results(ex, opt.into, n, P, f, out, st, pf);
      },
      true,
      mesh::IntoResult<3, Exec, decltype(out.triangles)>{
          bool(opt.into.triangles) || bool(opt.into.neighbors), out.triangles, out.neighbors});
}

// Points in executor memory, result left there (or in the caller's arrays of that memory).
inline void triangulate_device_impl(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                                    DeviceOutput& out, Delaunay2dStats& st,
                                    const ::gpugeom::detail::ExecContext* outer) {
  Exec ex(opt, outer);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint - 16,
                                           "a 2D Delaunay triangulation", "points");
  triangulate_core(
      ex, xy, n, true, opt.profile, st, [](Prepared&) {},
      [&](Prepared& P, typename Triangulator::Finished& f) {
        const Triangulation2dBuffers& into = opt.into;
        check_into(into, f.count, n);
        if (!P.dup.size() && !into.duplicate_of)  // no duplicates: all -1
          P.dup = ex.template alloc<std::int32_t>(std::size_t(n));
        std::int32_t* dup = P.dup.size() ? P.dup.data() : into.duplicate_of.data;
        if (!P.duplicates) ex.fill(dup, n, std::int32_t(-1));
        auto tri = deliver::place(ex, f.simplices, 3 * f.count, into.triangles);
        auto nb = deliver::place(ex, f.neighbors, 3 * f.count, into.neighbors);
        auto dp = deliver::place(ex, P.dup, P.dup.size() ? n : 0, into.duplicate_of);
        ex.sync();  // the caller may read them now (and free them on any stream)
        out.num_triangles = f.count;
        out.num_duplicates = P.duplicates;
        out.triangles = tri.own();
        out.neighbors = nb.own();
        out.duplicate_of = dp.own();
      });
}

// The Triangulator from a start (executor memory: f triangles of input indices, mapped to
// prepared indices in place, their twins, and per input point a start vertex near it or null),
// after prepare(P); the result left on the executor for finish(). kernel, when given, is the
// kernel point to use (strictly inside the start's hull under the perturbation), else one is
// placed inside the start's first triangle.
inline typename Triangulator::Finished run_from_start(
    Exec& ex, Prepared& P, std::int64_t n, std::int32_t* tris, std::int64_t f,
    const std::int32_t* twin, const std::int32_t* hint, bool profile, Delaunay2dStats& st,
    const double* kernel = nullptr, bool peel_flats = true, bool start_delaunay = false) {
  auto t0 = std::chrono::steady_clock::now();
  // Input index -> prepared index (a duplicate's: the point kept for it).
  auto d_inv = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* inv = d_inv.data();
  const std::int32_t* orig = P.orig.data();
  const std::int32_t* dup = P.duplicates ? P.dup.data() : nullptr;
  ex.for_each_index(
      P.m, GG_LAMBDA(std::int64_t j) { inv[orig[j]] = std::int32_t(j); });
  if (dup)
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          if (dup[i] >= 0) inv[i] = inv[dup[i]];
        });
  ex.for_each_index(
      3 * f, GG_LAMBDA(std::int64_t e) { tris[e] = inv[tris[e]]; });
  // The hints in prepared indices too (a point's own entry at its prepared index).
  auto d_near = ex.template alloc<std::int32_t>(hint ? std::size_t(P.m) : 0);
  std::int32_t* near = d_near.data();
  if (hint) {
    ex.fill(near, P.m, std::int32_t(-1));
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          if ((!dup || dup[i] < 0) && hint[i] >= 0 && hint[i] < n) near[inv[i]] = inv[hint[i]];
        });
  }
  // The kernel point: the one given (strictly inside the start's hull), else one inside the
  // start's first triangle.
  if (kernel) {
    P.kernel[0] = kernel[0], P.kernel[1] = kernel[1];
  } else {
    std::int32_t id[3];
    ex.to_host(tris, 3, id);
    double p[3][2];
    for (int k = 0; k < 3; ++k) ex.to_host(P.pts.data() + 2 * std::int64_t(id[k]), 2, p[k]);
    const double* v[3] = {p[0], p[1], p[2]};
    if (!kernel_point(v, id, std::int32_t(P.m), P.kernel))
      throw Error(ErrorCode::InvalidArgument,
                  "start triangulation: no kernel point inside its first triangle");
  }
  d_inv = {};
  ex.sync();
  st.phase_ms.push_back({"start_map", ms_since(t0)});
  Triangulator T(ex, P, st, profile);
  T.run_from(tris, twin, f, hint ? near : nullptr, peel_flats, start_delaunay);
  t0 = std::chrono::steady_clock::now();
  T.report();
  T.release_work();
  auto out = T.finish();
  st.phase_ms.push_back({"finish", ms_since(t0)});
  return out;
}
