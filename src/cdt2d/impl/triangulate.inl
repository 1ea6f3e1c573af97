// The constrained Delaunay triangulation on one executor; included inside
// gpugeom::cdt::{cpu,cuda}_impl after recover.inl and domain.inl, with `dt_impl` naming
// delaunay2d's backend for the same executor.

// Points and segments in the executor's memory (segment indices checked) to the result in the
// executor's memory: the Delaunay triangulation (delaunay2d's device entry), the segments
// recovered, and the domain where asked for. Stops early when two segments cross (rc.cross_a).
inline void triangulate_core(Exec& ex, const double* pts, std::int64_t n, const std::int32_t* sp,
                             std::int64_t nseg, const Cdt2dOptions& opt,
                             DeviceConstrainedTriangulation2d& out, RecoveryCounts& rc) {
  Cdt2dStats& st = out.stats;
  const auto t0 = Clock::now();
  Delaunay2dOptions dopt = options_from<Delaunay2dOptions>(opt);
  del2d::DeviceOutput dt;
  Delaunay2dStats dst;
  const ::gpugeom::detail::ExecContext ctx = ex.context();  // (one stream, one memory count)
  dt_impl::entries.device(pts, n, dopt, dt, dst, &ctx);
  static_cast<Delaunay2dStats&>(st) = dst;  // (its counters are the CDT's too)
  st.phase_ms = {{"delaunay", ms_since(t0)}};
  const auto t1 = Clock::now();
  const std::int64_t nt = dt.num_triangles;
  auto seg = ex.template alloc<std::int32_t>(3 * std::size_t(nt));
  ex.fill(seg.data(), 3 * nt, std::int32_t(-1));
  auto vt = ex.template alloc<std::int32_t>(std::size_t(n));
  const MeshView m{pts, dt.triangles.get(), dt.neighbors.get(), seg.data(), vt.data()};
  recover_segments(ex, m, nt, sp, nseg, dt.duplicate_of.get(), rc);
  ex.sync();
  if (rc.cross_a >= 0) return;
  st.phase_ms.push_back({"segments", ms_since(t1)});
  out.num_points = n;
  out.num_duplicates = dt.num_duplicates;
  out.duplicate_of = dt.duplicate_of;
  out.num_triangles = nt;
  if (opt.domain != Cdt2dOptions::Domain::ConvexHull || !opt.holes.empty() ||
      !opt.regions.empty()) {
    // Holes, the outside and regions: the kept triangles compacted.
    const auto t3 = Clock::now();
    DomainResult dom = apply_domain(ex, m, nt, opt);
    ex.sync();
    out.num_triangles = dom.kept;
    out.removed_triangles = nt - dom.kept;
    out.triangles = dom.tri.hand_over();
    out.neighbors = dom.nbr.hand_over();
    out.segment_of = dom.seg.hand_over();
    if (!opt.regions.empty()) out.attribute = dom.attribute.hand_over();
    st.phase_ms.push_back({"domain", ms_since(t3)});
  } else {
    out.triangles = dt.triangles;
    out.neighbors = dt.neighbors;
    out.segment_of = seg.hand_over();
  }
}

// The outputs' lengths, checked against the caller's arrays before any is written.
inline void check_into(const Cdt2dBuffers& into, const DeviceConstrainedTriangulation2d& d) {
  deliver::check(into.triangles, 3 * d.num_triangles, "triangles");
  deliver::check(into.neighbors, 3 * d.num_triangles, "neighbors");
  deliver::check(into.segment_of, 3 * d.num_triangles, "segment_of");
  deliver::check(into.duplicate_of, d.num_points, "duplicate_of");
  if (d.attribute) deliver::check(into.attribute, d.num_triangles, "attribute");
}

// Host points and segments in, host arrays out (the caller's, opt.into, or the result's).
inline void triangulate_impl(const double* xy, std::int64_t n, const std::int32_t* segments,
                             std::int64_t nseg, const Cdt2dOptions& opt,
                             ConstrainedTriangulation2d& r, RecoveryCounts& rc) {
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, r.stats);  // (the whole call's)
  const Cdt2dBuffers& into = opt.into;
  // On the GPU the host is idle meanwhile: the result arrays are sized for the most triangles n
  // points can have (cut to the count later, keeping the pages) and faulted in by host threads,
  // so that the copy back runs at the transfer's rate (as delaunay2d's host entry does).
  detail::Prefault pf;
  if constexpr (Exec::backend == Backend::Cuda) {
    const std::size_t bound = 3 * std::size_t(delaunay2d_max_triangles(n));
    auto size = [&](HostVector<std::int32_t>& v, const OutBuffer<std::int32_t>& mine,
                    std::size_t len) {
      if (mine) return;
      v.resize(len);
      pf.add(v.data(), len * sizeof(std::int32_t));
    };
    size(r.triangles, into.triangles, bound);
    size(r.neighbors, into.neighbors, bound);
    size(r.segment_of, into.segment_of, bound);
    size(r.duplicate_of, into.duplicate_of, std::size_t(n));
    pf.start();
  }
  // The points and segments where the executor reads them (the CPU executor reads the
  // caller's).
  typename Exec::template Buffer<double> dxy;
  typename Exec::template Buffer<std::int32_t> dsegs;
  const double* pts = xy;
  const std::int32_t* sp = segments;
  if constexpr (Exec::backend != Backend::Cpu) {
    dxy = ex.template alloc<double>(2 * std::size_t(n));
    ex.from_host(xy, 2 * n, dxy.data());
    pts = dxy.data();
    dsegs = ex.template alloc<std::int32_t>(std::size_t(2 * std::max<std::int64_t>(nseg, 1)));
    ex.from_host(segments, 2 * nseg, dsegs.data());
    sp = dsegs.data();
  }
  DeviceConstrainedTriangulation2d d;
  triangulate_core(ex, pts, n, sp, nseg, opt, d, rc);
  r.stats = std::move(d.stats);
  if (rc.cross_a >= 0) return;
  const auto t2 = Clock::now();
  pf.wait();
  r.stats.phase_ms.push_back({"prefault_wait", ms_since(t2)});
  check_into(into, d);
  const std::int64_t c3 = 3 * d.num_triangles;
  deliver::to_host(ex, d.triangles.get(), c3, into.triangles, r.triangles);
  deliver::to_host(ex, d.neighbors.get(), c3, into.neighbors, r.neighbors);
  deliver::to_host(ex, d.segment_of.get(), c3, into.segment_of, r.segment_of);
  if (d.attribute)
    deliver::to_host(ex, d.attribute.get(), d.num_triangles, into.attribute, r.attribute);
  deliver::to_host(ex, d.duplicate_of.get(), n, into.duplicate_of, r.duplicate_of);
  r.num_triangles = d.num_triangles;
  r.num_duplicates = d.num_duplicates;
  r.removed_triangles = d.removed_triangles;
  r.stats.phase_ms.push_back({"to_host", ms_since(t2)});
}

// Points and segments in the executor's memory, the result left there (or in the caller's
// arrays of that memory, opt.into). Segment indices are checked on the executor.
inline void triangulate_device_impl(const double* xy, std::int64_t n, const std::int32_t* segments,
                                    std::int64_t nseg, const Cdt2dOptions& opt,
                                    DeviceConstrainedTriangulation2d& r, RecoveryCounts& rc) {
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, r.stats);  // (the whole call's)
  check_segment_indices(ex, segments, nseg, n);
  triangulate_core(ex, xy, n, segments, nseg, opt, r, rc);
  if (rc.cross_a >= 0) return;
  const Cdt2dBuffers& into = opt.into;
  check_into(into, r);
  // The library's arrays whose contents were copied into the caller's: they leave the result,
  // and are freed once the copies are done (triangulate_core has waited for the rest).
  std::vector<std::shared_ptr<const void>> copied;
  auto place = [&](auto& mine, std::int64_t len, const auto& theirs) {
    if (deliver::place_shared(ex, mine, len, theirs)) copied.push_back(std::move(mine));
  };
  const std::int64_t c3 = 3 * r.num_triangles;
  place(r.triangles, c3, into.triangles);
  place(r.neighbors, c3, into.neighbors);
  place(r.segment_of, c3, into.segment_of);
  place(r.duplicate_of, n, into.duplicate_of);
  if (r.attribute) place(r.attribute, r.num_triangles, into.attribute);
  if (!copied.empty()) ex.sync();  // the caller may read its arrays now
}
