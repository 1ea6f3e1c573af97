// Delaunay refinement's rounds on one executor; included inside
// gpugeom::refine::{cpu,cuda}_impl after rounds.inl and kept_mesh.inl, with `cdt_impl` naming
// cdt2d's backend for the same executor.
//
// The input's constrained Delaunay triangulation (cdt2d's device core, exact) is made once and
// kept; every round decides from it (rounds.inl), inserts the chosen splits and points into it,
// and flips it back to constrained Delaunay (kept_mesh.inl). The loop ends when a round has
// nothing to insert: the kept triangulation is the mesh.

// What refinement hands back, in the executor's memory (report lists on the host).
struct Output {
  Buf<double> xy, attribute;
  Buf<std::int32_t> tri, nbr, seg, dup, sub, sub_of;
  std::int64_t np = 0, nt = 0, nsub = 0, removed = 0;
  std::vector<std::int32_t> small, large;
  std::vector<std::int8_t> reasons;
  Tally tally;  // rounds, counts and phase times
};

// The kept mesh as the output: marks as base segments' final names (final_of_base: input
// segment or RefinedMesh2d::kHullSegment), region attributes as given, the input points'
// duplicate_of (dup, n entries; new points never repeat one), and the triangles left bad.
inline void finish(Exec& ex, const Kept& K, const std::int32_t* dup, std::int64_t n,
                   std::int64_t removed, const Decisions& d,
                   const std::vector<std::int32_t>& final_of_base, const Refine2dOptions& opt,
                   Output& out) {
  const std::int64_t nt = K.nt, np = K.np;
  out.np = np;
  out.nt = nt;
  out.removed = removed;
  out.xy = ex.template alloc<double>(2 * std::size_t(std::max<std::int64_t>(np, 1)));
  ex.copy(K.xy.data(), 2 * np, out.xy.data());
  out.tri = ex.template alloc<std::int32_t>(3 * std::size_t(std::max<std::int64_t>(nt, 1)));
  out.nbr = ex.template alloc<std::int32_t>(3 * std::size_t(std::max<std::int64_t>(nt, 1)));
  out.seg = ex.template alloc<std::int32_t>(3 * std::size_t(std::max<std::int64_t>(nt, 1)));
  out.dup = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(np, 1)));
  ex.copy(K.tri.data(), 3 * nt, out.tri.data());
  ex.copy(K.nbr.data(), 3 * nt, out.nbr.data());
  ex.copy(dup, n, out.dup.data());
  ex.fill(out.dup.data() + n, np - n, std::int32_t(-1));
  auto fob = ex.template alloc<std::int32_t>(std::max<std::size_t>(final_of_base.size(), 1));
  ex.from_host(final_of_base.data(), std::int64_t(final_of_base.size()), fob.data());
  {
    const std::int32_t *S = K.seg.data(), *N = K.nbr.data(), *T = K.tri.data();
    const std::int32_t *FB = fob.data(), *SB = K.sub_base.data();
    std::int32_t* G = out.seg.data();
    // The subsegments as a list (what Triangle returns as its segments), in index order, each
    // from the triangle with the lower index.
    const std::int64_t ns = K.nsub;
    out.nsub = ns;
    out.sub = ex.template alloc<std::int32_t>(2 * std::size_t(std::max<std::int64_t>(ns, 1)));
    out.sub_of = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(ns, 1)));
    std::int32_t *SE = out.sub.data(), *SO = out.sub_of.data();
    ex.for_each_index(
        3 * nt, GG_LAMBDA(std::int64_t e) {
          const std::int32_t j = S[e];
          G[e] = j < 0 ? -1 : FB[SB[j]];
          if (j < 0 || !(N[e] < 0 || e / 3 < N[e])) return;
          const std::int64_t t = e / 3;
          SE[2 * j] = T[3 * t + (e % 3 + 1) % 3];
          SE[2 * j + 1] = T[3 * t + (e % 3 + 2) % 3];
        });
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t j) { SO[j] = FB[SB[j]]; });
  }
  if (!opt.regions.empty()) {
    std::vector<double> attr;
    for (const auto& g : opt.regions) attr.push_back(g.attribute);
    auto da = ex.template alloc<double>(attr.size());
    ex.from_host(attr.data(), std::int64_t(attr.size()), da.data());
    out.attribute = ex.template alloc<double>(std::size_t(std::max<std::int64_t>(nt, 1)));
    const double *A = K.attr.data(), *DA = da.data();
    double* OA = out.attribute.data();
    ex.for_each_index(
        nt, GG_LAMBDA(std::int64_t t) {
          const std::int64_t r = std::int64_t(A[t]);
          OA[t] = r > 0 ? DA[r - 1] : 0.0;
        });
  }
  // The bad triangles left (few): their indices and reasons, to the host.
  auto list = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(nt, 1)));
  auto cnt = ex.template alloc<std::int64_t>(1);
  for (int which = 0; which < 2; ++which) {
    const std::int8_t* R = which == 0 ? d.reason.data() : d.large.data();
    ex.compact_indices_to(
        nt, GG_LAMBDA(std::int64_t t)->bool { return R[t] != 0; }, list.data(), cnt.data());
    std::int64_t k = 0;
    ex.to_host(cnt.data(), 1, &k);
    std::vector<std::int32_t>& dst = which == 0 ? out.small : out.large;
    dst.resize(std::size_t(k));
    ex.to_host(list.data(), k, dst.data());
  }
  std::vector<std::int8_t> all(static_cast<std::size_t>(nt));
  ex.to_host(d.reason.data(), nt, all.data());
  for (std::int32_t t : out.small) out.reasons.push_back(all[std::size_t(t)]);
}

// The hull's boundary edges on no segment, appended as new base segments (Triangle's -c:
// without Domain::Enclosed the convex hull bounds the mesh).
inline void add_boundary(Exec& ex, const DeviceConstrainedTriangulation2d& dr,
                         std::vector<std::int32_t>& base,
                         std::vector<std::int32_t>& final_of_base) {
  const std::size_t nt = std::size_t(dr.num_triangles);
  std::vector<std::int32_t> tri(3 * nt), nbr(3 * nt), seg(3 * nt);
  ex.to_host(dr.triangles.get(), 3 * dr.num_triangles, tri.data());
  ex.to_host(dr.neighbors.get(), 3 * dr.num_triangles, nbr.data());
  ex.to_host(dr.segment_of.get(), 3 * dr.num_triangles, seg.data());
  for (std::size_t e = 0; e < tri.size(); ++e) {
    if (nbr[e] >= 0 || seg[e] >= 0) continue;
    const std::size_t t = e / 3, k = e % 3;
    base.insert(base.end(), {tri[3 * t + (k + 1) % 3], tri[3 * t + (k + 2) % 3]});
    final_of_base.push_back(RefinedMesh2d::kHullSegment);
  }
}

// Per triangle, the host sizing function's bound at its centroid.
inline void host_sizes(Exec& ex, const RoundMesh& m, std::int64_t np,
                       const std::function<double(double, double)>& f, Buf<double>& out) {
  std::vector<std::int32_t> tri(3 * std::size_t(m.nt));
  std::vector<double> xy(2 * std::size_t(np)), a(std::size_t(m.nt));
  ex.to_host(m.tri, 3 * m.nt, tri.data());
  ex.to_host(m.xy, 2 * np, xy.data());
  for (std::size_t t = 0; t < a.size(); ++t) {
    double cx = 0, cy = 0;
    for (int k = 0; k < 3; ++k)
      cx += xy[2 * std::size_t(tri[3 * t + k])], cy += xy[2 * std::size_t(tri[3 * t + k]) + 1];
    const double v = f(cx / 3, cy / 3);
    a[t] = std::isfinite(v) && v > 0 ? v : 0.0;
  }
  out = ex.template alloc<double>(std::max<std::size_t>(a.size(), 1));
  ex.from_host(a.data(), std::int64_t(a.size()), out.data());
}

// Per input vertex: 0, or kCorner where two or more base segments end (their subsegments are
// split on concentric shells), kAcute where two of them meet at less than 60 degrees (a small
// input angle: the terminator's rules apply there). Host code, once per call.
inline std::vector<std::int8_t> corner_kinds(Exec& ex, const double* dxy, std::int64_t n,
                                             const std::vector<std::int32_t>& base) {
  std::vector<double> xy(2 * static_cast<std::size_t>(n));
  ex.to_host(dxy, 2 * n, xy.data());
  std::vector<std::vector<double>> dirs(static_cast<std::size_t>(n));
  for (std::size_t j = 0; j + 1 < base.size(); j += 2) {
    const std::int32_t a = base[j], b = base[j + 1];
    if (a == b) continue;
    const double dx = xy[2 * std::size_t(b)] - xy[2 * std::size_t(a)];
    const double dy = xy[2 * std::size_t(b) + 1] - xy[2 * std::size_t(a) + 1];
    if (dx == 0 && dy == 0) continue;
    dirs[std::size_t(a)].push_back(std::atan2(dy, dx));
    dirs[std::size_t(b)].push_back(std::atan2(-dy, -dx));
  }
  std::vector<std::int8_t> kind(static_cast<std::size_t>(n), 0);
  const double pi = 3.14159265358979323846;
  for (std::size_t v = 0; v < dirs.size(); ++v) {
    auto& d = dirs[v];
    if (d.size() < 2) continue;
    std::sort(d.begin(), d.end());
    double gap = d.front() + 2 * pi - d.back();
    for (std::size_t i = 1; i < d.size(); ++i) gap = std::min(gap, d[i] - d[i - 1]);
    kind[v] = gap < pi / 3 ? kAcute : kCorner;
  }
  return kind;
}

// xy (n points) and segs (nseg pairs) in the executor's memory. final_of_base: per given
// segment, the name its marks take in the output. Stops early, out untouched, when two segments
// cross (rc.cross_a).
inline void refine_core(Exec& ex, const double* xy, std::int64_t n, const std::int32_t* segs,
                        std::int64_t nseg, std::vector<std::int32_t> final_of_base,
                        const Refine2dOptions& opt, Output& out, cdt::RecoveryCounts& rc) {
  std::vector<std::int32_t> base(2 * std::size_t(nseg));
  ex.to_host(segs, 2 * nseg, base.data());

  Cdt2dOptions copt = options_from<Cdt2dOptions>(opt);
  copt.domain = opt.domain;
  copt.holes = opt.holes;
  for (std::size_t i = 0; i < opt.regions.size(); ++i)
    copt.regions.push_back({opt.regions[i].x, opt.regions[i].y, double(i + 1), 0.0});
  std::vector<double> region_area;
  for (const auto& g : opt.regions) region_area.push_back(g.max_area);
  auto dregion = ex.template alloc<double>(std::max<std::size_t>(region_area.size(), 1));
  ex.from_host(region_area.data(), std::int64_t(region_area.size()), dregion.data());
  const AreaGrid& ag = opt.area_grid;
  const bool grid = ag.rows > 0 && ag.cols > 0;
  auto dgrid = ex.template alloc<double>(grid ? ag.values.size() : 1);
  if (grid) ex.from_host(ag.values.data(), std::int64_t(ag.values.size()), dgrid.data());
  Bounds bounds;
  if (opt.min_angle > 0) {
    const double r = opt.min_angle * 3.14159265358979323846 / 180;
    bounds.sin2 = std::sin(r) * std::sin(r);
    // 95 % of the height at which the shortest edge subtends the bound exactly: the new triangle
    // is then strictly good despite rounding (on the bound exactly, half would come out bad and
    // be split again); Triangle uses the same margin.
    bounds.cot_half = 0.475 / std::tan(r / 2);
    bounds.lens = std::cos(2 * r) * std::cos(2 * r);
  }
  bounds.max_area = opt.max_area > 0 ? opt.max_area : 0;
  if (!region_area.empty()) bounds.region_area = dregion.data();
  if (grid) {
    bounds.grid = dgrid.data();
    bounds.rows = ag.rows, bounds.cols = ag.cols;
    bounds.x0 = ag.x0, bounds.y0 = ag.y0, bounds.x1 = ag.x1, bounds.y1 = ag.y1;
  }

  // With no bound at all there is nothing to refine (not even encroached subsegments: Triangle
  // splits them only for -q or -a): the constrained triangulation is the mesh.
  bool bounded = bounds.sin2 > 0 || bounds.max_area > 0 || grid || bool(opt.max_area_at);
  for (double a : region_area) bounded = bounded || a > 0;

  // The input's constrained triangulation; where the convex hull bounds the domain, its edges
  // become segments first and the domain is what they enclose. Its marks are base indices.
  Tally& tl = out.tally;
  auto tick = Clock::now();
  auto lap = [&tick](double& into) {
    const auto now = Clock::now();
    into += std::chrono::duration<double, std::milli>(now - tick).count();
    tick = now;
  };
  DeviceConstrainedTriangulation2d dr;
  rc = {};
  cdt_impl::entries.triangulate_device(xy, n, segs, nseg, copt, dr, rc);
  if (rc.cross_a >= 0) return;
  if (opt.domain == Cdt2dOptions::Domain::ConvexHull) {
    add_boundary(ex, dr, base, final_of_base);
    auto dsegs = ex.template alloc<std::int32_t>(std::max<std::size_t>(base.size(), 2));
    ex.from_host(base.data(), std::int64_t(base.size()), dsegs.data());
    copt.domain = Cdt2dOptions::Domain::Enclosed;
    dr = {};
    rc = {};
    cdt_impl::entries.triangulate_device(xy, n, dsegs.data(), std::int64_t(base.size() / 2), copt,
                                         dr, rc);
    if (rc.cross_a >= 0) return;
  }
  Kept K = kept_from(ex, xy, n, dr);
  auto dbase = ex.template alloc<std::int32_t>(std::max<std::size_t>(base.size(), 2));
  ex.from_host(base.data(), std::int64_t(base.size()), dbase.data());
  const std::vector<std::int8_t> kinds = corner_kinds(ex, xy, n, base);
  auto corner = ex.template alloc<std::int8_t>(std::max<std::size_t>(kinds.size(), 1));
  ex.from_host(kinds.data(), std::int64_t(kinds.size()), corner.data());
  ex.sync();
  lap(tl.cdt_ms);

  bool last = !bounded;
  constexpr std::int64_t kStall = 64;
  double best_share = 2;
  std::int64_t best_round = 0;
  const std::int64_t room = opt.max_steiner_points;
  auto counts = ex.template alloc<std::int64_t>(5);
  const Corners cn{corner.data(), n};
  for (std::int64_t round = 0;; ++round) {
    const RoundMesh m = K.view();  // (the kept arrays move when they grow: views per round)
    const Terminator tm{K.on_base.data(), dbase.data(), corner.data(), n};
    const std::size_t tn = std::size_t(std::max<std::int64_t>(m.nt, 1));
    const std::size_t sn = std::size_t(std::max<std::int64_t>(K.nsub, 1));
    Decisions d;
    d.split = ex.template alloc<std::int32_t>(sn);
    d.half = ex.template alloc<std::int32_t>(sn);
    d.point = ex.template alloc<double>(2 * tn);
    d.land = ex.template alloc<std::int32_t>(tn);
    d.key = ex.template alloc<std::uint64_t>(tn);
    d.reason = ex.template alloc<std::int8_t>(tn);
    d.large = ex.template alloc<std::int8_t>(tn);
    d.rejected = ex.template alloc<std::int8_t>(tn);
    ex.fill(d.split.data(), K.nsub, std::int32_t(0));
    ex.fill(d.half.data(), K.nsub, std::numeric_limits<std::int32_t>::max());
    Buf<double> sizes;
    Bounds b = bounds;
    if (opt.max_area_at) {
      host_sizes(ex, m, K.np, opt.max_area_at, sizes);
      b.triangle_area = sizes.data();
    }
    bool stalled = false;
    Choice ch;
    Buf<std::int32_t> cand;  // (the choice's points index it until they are inserted)
    if (!last) {
      // The candidates (written since judged, or still bad), judged; the choice; and in the same
      // read the bad triangles refinement still works on (the terminator's excepted) and the
      // points rejected for encroaching (above bit 32).
      cand = ex.template alloc<std::int32_t>(tn);
      const std::int8_t* DI = K.dirty.data();
      ex.compact_indices_to(
          m.nt, GG_LAMBDA(std::int64_t t)->bool { return DI[t] != 0; }, cand.data(),
          counts.data() + 4);
      std::int64_t nc = 0;
      ex.to_host(counts.data() + 4, 1, &nc);
      find_bad(ex, m, cand.data(), nc, b, tm, cn, d, K.dirty.data());
      ch = choose(ex, m, d, cand.data(), nc, K.nsub, corner.data(), n, counts.data());
      const std::int8_t *R = d.reason.data(), *LG = d.large.data(), *RJ = d.rejected.data();
      const std::int32_t* CA = cand.data();
      ex.transform_reduce_into(
          nc,
          GG_LAMBDA(std::int64_t i)->std::int64_t {
            const std::int32_t t = CA[i];
            const bool bad = R[t] == std::int8_t(SmallAngle::Limit) || LG[t];
            return (std::int64_t(RJ[t]) << 32) + (bad ? 1 : 0);
          },
          std::int64_t(0), thrust::plus<std::int64_t>(), counts.data() + 3);
      std::int64_t c[4] = {0, 0, 0, 0};
      if (nc > 0) ex.to_host(counts.data(), 4, c);
      ch.nsplits = c[0], ch.npoints = c[1], ch.split_tris = c[2];
      const std::int64_t h[2] = {c[3] & 0xffffffff, c[3] >> 32};
      out.tally.rejected += h[1];
      // Refinement whose share of bad triangles has not fallen for kStall rounds has stalled
      // (near the angle limit new points can make bad triangles as fast as they remove them):
      // it stops, the bad triangles reported as Limit, rather than run on without end. (The
      // share, not the count: refining to an area bound multiplies the large triangles for many
      // rounds before their number falls.)
      const double share = double(h[0]) / double(std::max<std::int64_t>(m.nt, 1));
      if (share < best_share) best_share = share, best_round = round;
      if (round - best_round > kStall) stalled = true;
    }
    // Nothing left to insert (or the Steiner limit reached): the kept triangulation is the mesh,
    // every triangle judged once more for the report.
    if (last || stalled || ch.nsplits + ch.npoints == 0) {
      std::int64_t broken = 0;
      ex.to_host(K.broken.data(), 1, &broken);
      if (broken)
        throw Error(ErrorCode::Internal, "refine2d: the kept triangulation lost " +
                                             std::to_string(broken) + " edge twins (a bug)");
      out.tally.rounds = round + 1;
      find_bad(ex, m, nullptr, m.nt, b, tm, cn, d, K.dirty.data());
      lap(tl.decide_ms);
      finish(ex, K, dr.duplicate_of.get(), n, dr.removed_triangles, d, final_of_base, opt, out);
      ex.sync();
      lap(tl.output_ms);
      return;
    }
    const std::int64_t avail =
        room < 0 ? std::int64_t(1) << 62 : std::max<std::int64_t>(0, room - (K.np - n));
    const std::int64_t nsw = std::min(ch.nsplits, avail);
    const std::int64_t npw = std::min(ch.npoints, avail - nsw);
    lap(tl.decide_ms);
    std::int64_t nlist = 0;
    Buf<std::int32_t> list =
        insert_chosen(ex, K, ch, d, nsw, npw, nsw == ch.nsplits ? ch.split_tris : -1, nlist);
    tl.flips += flip_until_legal(ex, K, std::move(list), nlist, tl.flip_passes);
    lap(tl.insert_ms);
    out.tally.splits += nsw;
    out.tally.points += npw;
    if (room >= 0 && K.np - n >= room) last = true;
  }
}

// The outputs' lengths against the caller's arrays (opt.into), before any is written.
inline void check_into(const Refine2dBuffers& into, const Output& o, bool regions) {
  deliver::check(into.points, 2 * o.np, "points");
  deliver::check(into.triangles, 3 * o.nt, "triangles");
  deliver::check(into.neighbors, 3 * o.nt, "neighbors");
  deliver::check(into.segment_of, 3 * o.nt, "segment_of");
  deliver::check(into.duplicate_of, o.np, "duplicate_of");
  deliver::check(into.subsegments, 2 * o.nsub, "subsegments");
  deliver::check(into.subsegment_of, o.nsub, "subsegment_of");
  if (regions) deliver::check(into.attribute, o.nt, "attribute");
}

// Host arrays in (checked), host arrays out.
inline void refine_host(const double* xy, std::int64_t n, const std::int32_t* segs,
                        std::int64_t nseg, const std::vector<std::int32_t>& final_of_base,
                        const Refine2dOptions& opt, RefinedMesh2d& r, cdt::RecoveryCounts& rc,
                        Tally& tally) {
  Exec ex(opt);
  auto dxy = ex.template alloc<double>(2 * std::size_t(std::max<std::int64_t>(n, 1)));
  auto dsegs = ex.template alloc<std::int32_t>(2 * std::size_t(std::max<std::int64_t>(nseg, 1)));
  ex.from_host(xy, 2 * n, dxy.data());
  ex.from_host(segs, 2 * nseg, dsegs.data());
  Output o;
  const auto t0 = Clock::now();
  refine_core(ex, dxy.data(), n, dsegs.data(), nseg, final_of_base, opt, o, rc);
  if (rc.cross_a >= 0) return;
  r.stats.phase_ms.push_back({"refine", ms_since(t0)});
  const auto t1 = Clock::now();
  const Refine2dBuffers& into = opt.into;
  check_into(into, o, !opt.regions.empty());
  deliver::to_host(ex, o.xy.data(), 2 * o.np, into.points, r.points);
  deliver::to_host(ex, o.tri.data(), 3 * o.nt, into.triangles, r.triangles);
  deliver::to_host(ex, o.nbr.data(), 3 * o.nt, into.neighbors, r.neighbors);
  deliver::to_host(ex, o.seg.data(), 3 * o.nt, into.segment_of, r.segment_of);
  deliver::to_host(ex, o.dup.data(), o.np, into.duplicate_of, r.duplicate_of);
  deliver::to_host(ex, o.sub.data(), 2 * o.nsub, into.subsegments, r.subsegments);
  deliver::to_host(ex, o.sub_of.data(), o.nsub, into.subsegment_of, r.subsegment_of);
  if (!opt.regions.empty())
    deliver::to_host(ex, o.attribute.data(), o.nt, into.attribute, r.attribute);
  r.stats.phase_ms.push_back({"to_host", ms_since(t1)});
  r.small_angles.assign(o.small.begin(), o.small.end());
  r.small_angle_reasons.assign(o.reasons.begin(), o.reasons.end());
  r.large_triangles.assign(o.large.begin(), o.large.end());
  r.removed_triangles = o.removed;
  r.num_points = o.np;
  r.num_triangles = o.nt;
  tally = o.tally;
}

// Executor memory in (segment indices checked there), executor memory out.
inline void refine_device_impl(const double* xy, std::int64_t n, const std::int32_t* segs,
                               std::int64_t nseg, const Refine2dOptions& opt,
                               DeviceRefinedMesh2d& r, cdt::RecoveryCounts& rc, Tally& tally) {
  Exec ex(opt);
  check_segment_indices(ex, segs, nseg, n);
  std::vector<std::int32_t> final_of_base(static_cast<std::size_t>(nseg));
  for (std::int64_t j = 0; j < nseg; ++j) final_of_base[std::size_t(j)] = std::int32_t(j);
  Output o;
  refine_core(ex, xy, n, segs, nseg, final_of_base, opt, o, rc);
  if (rc.cross_a >= 0) return;
  r.num_points = o.np, r.num_input_points = n, r.num_triangles = o.nt;
  r.removed_triangles = o.removed;
  r.num_subsegments = o.nsub;
  const Refine2dBuffers& into = opt.into;
  const bool regions = !opt.regions.empty();
  check_into(into, o, regions);
  auto p_xy = deliver::place(ex, o.xy, 2 * o.np, into.points);
  auto p_tri = deliver::place(ex, o.tri, 3 * o.nt, into.triangles);
  auto p_nbr = deliver::place(ex, o.nbr, 3 * o.nt, into.neighbors);
  auto p_seg = deliver::place(ex, o.seg, 3 * o.nt, into.segment_of);
  auto p_dup = deliver::place(ex, o.dup, o.np, into.duplicate_of);
  auto p_sub = deliver::place(ex, o.sub, 2 * o.nsub, into.subsegments);
  auto p_sub_of = deliver::place(ex, o.sub_of, o.nsub, into.subsegment_of);
  auto p_att = regions ? deliver::place(ex, o.attribute, o.nt, into.attribute)
                       : deliver::Placed<Exec, double>{};
  ex.sync();  // the caller's arrays are written; the library's own go to the result
  r.points = p_xy.own();
  r.triangles = p_tri.own();
  r.neighbors = p_nbr.own();
  r.segment_of = p_seg.own();
  r.duplicate_of = p_dup.own();
  r.subsegments = p_sub.own();
  r.subsegment_of = p_sub_of.own();
  r.attribute = p_att.own();
  r.small_angles = std::move(o.small);
  r.small_angle_reasons = std::move(o.reasons);
  r.large_triangles = std::move(o.large);
  tally = o.tally;
}
