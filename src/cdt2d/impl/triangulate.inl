// The constrained Delaunay triangulation on one executor; included inside
// gpugeom::cdt::{cpu,cuda}_impl after recover.inl and domain.inl, with `dt_impl` naming
// delaunay2d's backend for the same executor.

// Points and segments in the executor's memory (segment indices checked) to the result in the
// executor's memory: the Delaunay triangulation (delaunay2d's device entry), the segments
// recovered, and the domain where asked for. Stops early when two segments cross (rc.cross_a).
inline void triangulate_core(Exec& ex, const double* pts, std::int64_t n, const std::int32_t* sp,
                             std::int64_t nseg, const Cdt2dOptions& opt, DeviceResult& out,
                             Stats& st, RecoveryCounts& rc) {
  const auto t0 = Clock::now();
  Delaunay2dOptions dopt;
  static_cast<RunOptions&>(dopt) = opt;
  del2d::DeviceOutput dt;
  Stats dst;
  dt_impl::entries.triangulate_device(pts, n, dopt, dt, dst);
  st = dst;
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
  out.num_duplicates = dt.num_duplicates;
  out.duplicate_of = dt.duplicate_of;
  out.count = nt;
  if (opt.domain != Cdt2dOptions::Domain::ConvexHull || !opt.holes.empty() ||
      !opt.regions.empty()) {
    // Holes, the outside and regions: the kept triangles compacted.
    const auto t3 = Clock::now();
    DomainResult dom = apply_domain(ex, m, nt, opt);
    ex.sync();
    out.count = dom.kept;
    out.removed = nt - dom.kept;
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

// Host points and segments in, host arrays out.
inline void triangulate_impl(const double* xy, std::int64_t n, const std::int32_t* segments,
                             std::int64_t nseg, const Cdt2dOptions& opt,
                             ConstrainedTriangulation2d& r, RecoveryCounts& rc) {
  Exec ex(opt);
  // On the GPU the host is idle meanwhile: the result arrays are sized for the most triangles n
  // points can have (cut to the count later, keeping the pages) and faulted in by host threads,
  // so that the copy back runs at the transfer's rate (as delaunay2d's host entry does).
  detail::Prefault pf;
  if constexpr (Exec::backend == Backend::Cuda) {
    const std::size_t bound = 3 * std::size_t(delaunay2d_max_triangles(n));
    for (HostVector<std::int32_t>* v : {&r.triangles, &r.neighbors, &r.segment_of}) {
      v->resize(bound);
      pf.add(v->data(), bound * sizeof(std::int32_t));
    }
    r.duplicate_of.resize(std::size_t(n));
    pf.add(r.duplicate_of.data(), std::size_t(n) * sizeof(std::int32_t));
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
  DeviceResult d;
  triangulate_core(ex, pts, n, sp, nseg, opt, d, r.stats, rc);
  if (rc.cross_a >= 0) return;
  const auto t2 = Clock::now();
  pf.wait();
  r.stats.phase_ms.push_back({"prefault_wait", ms_since(t2)});
  deliver::to_host(ex, d.triangles.get(), 3 * d.count, OutBuffer<std::int32_t>{}, r.triangles);
  deliver::to_host(ex, d.neighbors.get(), 3 * d.count, OutBuffer<std::int32_t>{}, r.neighbors);
  deliver::to_host(ex, d.segment_of.get(), 3 * d.count, OutBuffer<std::int32_t>{}, r.segment_of);
  if (d.attribute)
    deliver::to_host(ex, d.attribute.get(), d.count, OutBuffer<double>{}, r.attribute);
  deliver::to_host(ex, d.duplicate_of.get(), n, OutBuffer<std::int32_t>{}, r.duplicate_of);
  r.num_duplicates = d.num_duplicates;
  r.removed_triangles = d.removed;
  r.stats.phase_ms.push_back({"to_host", ms_since(t2)});
}

// Points and segments in the executor's memory, the result left there. Segment indices are
// checked on the executor.
inline void triangulate_device_impl(const double* xy, std::int64_t n, const std::int32_t* segments,
                                    std::int64_t nseg, const Cdt2dOptions& opt, DeviceResult& d,
                                    Stats& st, RecoveryCounts& rc) {
  Exec ex(opt);
  check_segment_indices(ex, segments, nseg, n);
  triangulate_core(ex, xy, n, segments, nseg, opt, d, st, rc);
}
