// The 2D Delaunay module's phases entered one by one from host arrays, for the tests only
// (testing.hpp): included after delaunay2d/impl/unit.inl inside the executor's namespace. The
// library runs the same phases on arrays it keeps on the executor (digital/impl/pipeline.inl).

// The held arrays brought to the host.
inline void download_sketch(Exec& ex, const HeldSketch& H, std::int64_t n, bool keep_colour,
                            digital::Sketch& s) {
  s.pixel.resize(std::size_t(n));
  ex.to_host(H.pixel.data(), n, s.pixel.data());
  s.missing.resize(std::size_t(H.nmiss));
  ex.to_host(H.missing.data(), H.nmiss, s.missing.data());
  s.site_of.resize(std::size_t(n));
  ex.to_host(H.site_of.data(), n, s.site_of.data());
  if (keep_colour) {
    s.colour.resize(std::size_t(s.width * s.height));
    ex.to_host(H.colour.data(), s.width * s.height, s.colour.data());
  }
  s.triangles.resize(std::size_t(3 * H.nt));
  ex.to_host(H.tri.data(), 3 * H.nt, s.triangles.data());
  s.twin.resize(std::size_t(3 * H.nt));
  ex.to_host(H.twin.data(), 3 * H.nt, s.twin.data());
}

// The sketch of host points, brought to the host (testing.hpp: digital_sketch).
inline void digital_sketch_dual_impl(const double* xy, std::int64_t n, const RunOptions& run,
                                     bool keep_colour, digital::Sketch& s) {
  Exec ex(run);
  auto pts = ex.template alloc<double>(std::size_t(2 * n));
  ex.from_host(xy, 2 * n, pts.data());
  const HeldSketch H = sketch_on(ex, pts.data(), n, s);
  download_sketch(ex, H, n, keep_colour, s);
}

// The held start brought to the host.
inline void download_start(Exec& ex, const HeldStart& S, std::int64_t n, digital::Start& out) {
  out.triangles.resize(std::size_t(3 * S.nt));
  out.twin.resize(std::size_t(3 * S.nt));
  out.hint.resize(std::size_t(n));
  ex.to_host(S.tri.data(), 3 * S.nt, out.triangles.data());
  ex.to_host(S.twin.data(), 3 * S.nt, out.twin.data());
  ex.to_host(S.hint.data(), n, out.hint.data());
}

// The shifting phase from a host sketch (testing.hpp: shift_sketch).
inline void digital_shift_impl(const double* xy, std::int64_t n, const digital::Sketch& sk,
                               const RunOptions& run, digital::Start& out) {
  Exec ex(run);
  auto pts = ex.template alloc<double>(std::size_t(2 * n));
  ex.from_host(xy, 2 * n, pts.data());
  HeldSketch H;
  auto up = [&](const std::vector<std::int32_t>& v) {
    auto b = ex.template alloc<std::int32_t>(v.size());
    ex.from_host(v.data(), std::int64_t(v.size()), b.data());
    return b;
  };
  H.pixel = up(sk.pixel), H.site_of = up(sk.site_of), H.colour = up(sk.colour);
  H.tri = up(sk.triangles), H.twin = up(sk.twin);
  H.nt = std::int64_t(sk.triangles.size() / 3);
  const HeldStart S = shift_on(ex, pts.data(), n, sk, H, out);
  download_start(ex, S, n, out);
}

// From a start triangulation (testing.hpp: triangulate_from), host points in, host arrays out.
inline void triangulate_from_impl(const double* xy, std::int64_t n, const std::int32_t* start,
                                  std::int64_t nstart, const std::int32_t* twin,
                                  const std::int32_t* hint, const Delaunay2dOptions& opt,
                                  Output& out, Delaunay2dStats& st) {
  if (nstart < 1) throw Error(ErrorCode::InvalidArgument, "start triangulation: no triangle");
  for (std::int64_t i = 0; i < 3 * nstart; ++i)
    if (start[i] < 0 || start[i] >= n)
      throw Error(ErrorCode::InvalidArgument, "start triangulation: vertex out of range");
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint,
                                           "a 2D Delaunay triangulation", "points");
  auto t0 = std::chrono::steady_clock::now();
  Prepared P = prepare(ex, xy, n, false);
  detail::Prefault pf;
  size_host_results(opt.into, n, P, out, pf);
  st.points = n;
  st.distinct_points = P.m;
  st.duplicates = P.duplicates;
  auto up = [&](const std::int32_t* h, std::int64_t len) {
    auto b = ex.template alloc<std::int32_t>(h ? std::size_t(len) : 0);
    if (h) ex.from_host(h, len, b.data());
    return b;
  };
  auto d_tris = up(start, 3 * nstart), d_twin = up(twin, 3 * nstart), d_hint = up(hint, n);
  if (!twin) {
    d_twin = ex.template alloc<std::int32_t>(std::size_t(3 * nstart));
    if (mesh::pair_half_edges(ex, d_tris.data(), nstart, d_twin.data()))
      throw Error(ErrorCode::InvalidArgument,
                  "start triangulation: an edge in three triangles or more");
  }
  ex.sync();
  st.phase_ms.push_back({"prepare", ms_since(t0)});
  auto f = run_from_start(ex, P, n, d_tris.data(), nstart, d_twin.data(),
                          hint ? d_hint.data() : nullptr, opt.profile, st);
  deliver_host_results(ex, opt.into, n, P, f, out, st, pf);
}

const testing::Entries testing_entries{&triangulate_from_impl, &digital_sketch_dual_impl,
                                       &digital_shift_impl};
