// The constrained Delaunay triangulation of the convex hull on one executor; included inside
// gpugeom::cdt::{cpu,cuda}_impl after recover.inl, with `dt_impl` naming delaunay2d's backend
// for the same executor.
inline void triangulate_impl(const double* xy, std::int64_t n, const std::int32_t* segments,
                             std::int64_t nseg, const Cdt2dOptions& opt,
                             ConstrainedTriangulation2d& r, RecoveryCounts& rc) {
  Exec ex(opt);
  const auto t0 = Clock::now();
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
  // The points where the executor reads them (the CPU executor reads the caller's).
  typename Exec::template Buffer<double> dxy;
  const double* pts = xy;
  if constexpr (Exec::backend != Backend::Cpu) {
    dxy = ex.template alloc<double>(2 * std::size_t(n));
    ex.from_host(xy, 2 * n, dxy.data());
    pts = dxy.data();
  }
  Delaunay2dOptions dopt;
  static_cast<RunOptions&>(dopt) = opt;
  del2d::DeviceOutput dt;
  Stats dst;
  dt_impl::triangulate_device(pts, n, dopt, dt, dst);
  r.stats = dst;
  r.stats.phase_ms = {{"delaunay", ms_since(t0)}};
  const auto t1 = Clock::now();
  const std::int64_t nt = dt.num_triangles;
  auto seg = ex.template alloc<std::int32_t>(3 * std::size_t(nt));
  ex.fill(seg.data(), 3 * nt, std::int32_t(-1));
  auto vt = ex.template alloc<std::int32_t>(std::size_t(n));
  typename Exec::template Buffer<std::int32_t> dsegs;
  const std::int32_t* sp = segments;
  if constexpr (Exec::backend != Backend::Cpu) {
    dsegs = ex.template alloc<std::int32_t>(std::size_t(2 * std::max<std::int64_t>(nseg, 1)));
    ex.from_host(segments, 2 * nseg, dsegs.data());
    sp = dsegs.data();
  }
  const MeshView m{pts, dt.triangles.get(), dt.neighbors.get(), seg.data(), vt.data()};
  recover_segments(ex, m, nt, sp, nseg, dt.duplicate_of.get(), rc);
  ex.sync();
  if (rc.cross_a >= 0) return;
  r.stats.phase_ms.push_back({"segments", ms_since(t1)});
  // Holes, the outside and regions, where asked for: the kept triangles compacted.
  DomainResult dom;
  const std::int32_t *tri = m.tri, *nbr = m.nbr, *sg = m.seg;
  std::int64_t count = nt;
  if (opt.domain != Cdt2dOptions::Domain::ConvexHull || !opt.holes.empty() ||
      !opt.regions.empty()) {
    const auto t3 = Clock::now();
    dom = apply_domain(ex, m, nt, opt);
    tri = dom.tri.data(), nbr = dom.nbr.data(), sg = dom.seg.data(), count = dom.kept;
    r.removed_triangles = nt - dom.kept;
    ex.sync();
    r.stats.phase_ms.push_back({"domain", ms_since(t3)});
  }
  const auto t2 = Clock::now();
  pf.wait();
  r.stats.phase_ms.push_back({"prefault_wait", ms_since(t2)});
  deliver::to_host(ex, tri, 3 * count, OutBuffer<std::int32_t>{}, r.triangles);
  deliver::to_host(ex, nbr, 3 * count, OutBuffer<std::int32_t>{}, r.neighbors);
  deliver::to_host(ex, sg, 3 * count, OutBuffer<std::int32_t>{}, r.segment_of);
  if (!opt.regions.empty())
    deliver::to_host(ex, dom.attribute.data(), count, OutBuffer<double>{}, r.attribute);
  deliver::to_host(ex, dt.duplicate_of.get(), n, OutBuffer<std::int32_t>{}, r.duplicate_of);
  r.num_duplicates = dt.num_duplicates;
  r.stats.phase_ms.push_back({"to_host", ms_since(t2)});
}
