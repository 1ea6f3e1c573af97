// Delaunay refinement's rounds on one executor; included inside
// gpugeom::refine::{cpu,cuda}_impl after rounds.inl, with `cdt_impl` naming cdt2d's backend for
// the same executor.
//
// Every round triangulates the current points and subsegments from scratch with cdt2d's device
// core (exact, and a function of the points and subsegments alone), decides (rounds.inl), and
// writes the next round's arrays. The loop ends when a round decides nothing: that round's
// triangulation is the mesh.

// The points and subsegments a round triangulates, and what refinement keeps per point.
struct State {
  Buf<double> xy;              // 2 np
  Buf<std::int8_t> free_pt;    // np: 1 for a Steiner point off the segments (removable)
  Buf<std::int32_t> on_base;   // np: the base segment a split vertex lies on, else -1
  Buf<std::int32_t> segs;      // 2 ns: the subsegments
  Buf<std::int32_t> seg_base;  // ns: each one's base segment
  std::int64_t np = 0, ns = 0;
};

struct Counts {
  std::int64_t splits = 0, points = 0, dropped = 0;
};

// The next round's points and subsegments: the kept points in order, then one vertex per split
// subsegment (in subsegment order), then the chosen new points (in triangle order); each split
// subsegment becomes its first half in place and its second half appended. `room` caps the new
// points (max_steiner_points).
inline Counts build_next(Exec& ex, State& st, const RoundMesh& m, const Subsegments& s,
                         const Decisions& d, const Buf<std::int32_t>& winners,
                         std::int64_t nwinners, const std::int8_t* corner, std::int64_t n_in,
                         std::int64_t room) {
  Counts c;
  const std::int64_t np = st.np, ns = s.count;
  // Kept points: all but the free points that encroach or repeat another, and never a
  // subsegment's end (a split vertex can fall exactly on a free point, which the triangulation
  // then takes as the segment's vertex).
  auto kidx = ex.template alloc<std::int32_t>(std::size_t(np) + 1);
  auto ends = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(np, 1)));
  std::int32_t* KI = kidx.data();
  {
    std::int32_t* END = ends.data();
    const std::int32_t* E = s.ends.data();
    ex.fill(END, np, std::int32_t(0));
    ex.for_each_index(
        2 * ns, GG_LAMBDA(std::int64_t i) { atomic_max(END + E[i], std::int32_t(1)); });
    const std::int32_t *drop = d.drop.data(), *dup = m.dup;
    const std::int8_t* F = st.free_pt.data();
    ex.exclusive_scan_of(
        np + 1,
        GG_LAMBDA(std::int64_t v)->std::int32_t {
          return v < np && (END[v] || (!drop[v] && !(F[v] && dup[v] >= 0))) ? 1 : 0;
        },
        KI);
  }
  std::int32_t kept = 0;
  ex.to_host(KI + np, 1, &kept);
  c.dropped = np - kept;
  // Split vertices, where a double lies strictly between the ends.
  auto mid = ex.template alloc<double>(2 * std::size_t(std::max<std::int64_t>(ns, 1)));
  auto sidx = ex.template alloc<std::int32_t>(std::size_t(ns) + 1);
  double* M = mid.data();
  std::int32_t* SI = sidx.data();
  {
    const std::int32_t *E = s.ends.data(), *split = d.split.data();
    const double* P = m.xy;
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t j) {
          if (!split[j]) return;
          const std::int32_t a = E[2 * j], b = E[2 * j + 1];
          split_point(P + 2 * std::int64_t(a), P + 2 * std::int64_t(b), a < n_in && corner[a],
                      b < n_in && corner[b], M + 2 * j);
        });
    ex.exclusive_scan_of(
        ns + 1,
        GG_LAMBDA(std::int64_t j)->std::int32_t {
          if (j >= ns || !split[j]) return 0;
          const double* a = P + 2 * std::int64_t(E[2 * j]);
          const double* b = P + 2 * std::int64_t(E[2 * j + 1]);
          const double* q = M + 2 * j;
          const bool at_end = (q[0] == a[0] && q[1] == a[1]) || (q[0] == b[0] && q[1] == b[1]);
          return at_end || !std::isfinite(q[0]) || !std::isfinite(q[1]) ? 0 : 1;
        },
        SI);
  }
  std::int32_t nsplit = 0;
  ex.to_host(SI + ns, 1, &nsplit);
  const std::int64_t steiner = std::int64_t(kept) - n_in;
  const std::int64_t avail =
      room < 0 ? std::int64_t(1) << 62 : std::max<std::int64_t>(0, room - steiner);
  c.splits = std::min<std::int64_t>(nsplit, avail);
  c.points = std::min<std::int64_t>(nwinners, avail - c.splits);
  const std::int64_t np2 = kept + c.splits + c.points, ns2 = ns + c.splits;
  State nx;
  nx.np = np2;
  nx.ns = ns2;
  nx.xy = ex.template alloc<double>(2 * std::size_t(std::max<std::int64_t>(np2, 1)));
  nx.free_pt = ex.template alloc<std::int8_t>(std::size_t(std::max<std::int64_t>(np2, 1)));
  nx.on_base = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(np2, 1)));
  nx.segs = ex.template alloc<std::int32_t>(2 * std::size_t(std::max<std::int64_t>(ns2, 1)));
  nx.seg_base = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(ns2, 1)));
  double* X = nx.xy.data();
  std::int8_t* F2 = nx.free_pt.data();
  std::int32_t *B2 = nx.on_base.data(), *S2 = nx.segs.data(), *SB2 = nx.seg_base.data();
  {
    const double* P = m.xy;
    const std::int8_t* F = st.free_pt.data();
    const std::int32_t* B = st.on_base.data();
    ex.for_each_index(
        np, GG_LAMBDA(std::int64_t v) {
          if (KI[v + 1] == KI[v]) return;
          const std::int64_t i = KI[v];
          X[2 * i] = P[2 * v];
          X[2 * i + 1] = P[2 * v + 1];
          F2[i] = F[v];
          B2[i] = B[v];
        });
  }
  {
    const std::int32_t *E = s.ends.data(), *SB = s.base.data();
    const std::int64_t nsp = c.splits;
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t j) {
          const std::int32_t a = KI[E[2 * j]], b = KI[E[2 * j + 1]];
          const std::int64_t r = SI[j];
          if (SI[j + 1] == r || r >= nsp) {
            S2[2 * j] = a, S2[2 * j + 1] = b, SB2[j] = SB[j];
            return;
          }
          const std::int32_t v = std::int32_t(kept + r);
          X[2 * v] = M[2 * j];
          X[2 * v + 1] = M[2 * j + 1];
          F2[v] = 0;
          B2[v] = SB[j];
          S2[2 * j] = a, S2[2 * j + 1] = v, SB2[j] = SB[j];
          S2[2 * (ns + r)] = v, S2[2 * (ns + r) + 1] = b, SB2[ns + r] = SB[j];
        });
  }
  {
    const std::int32_t* W = winners.data();
    const double* NP = d.point.data();
    const std::int64_t first = kept + c.splits;
    ex.for_each_index(
        c.points, GG_LAMBDA(std::int64_t i) {
          const std::int64_t t = W[i], v = first + i;
          X[2 * v] = NP[2 * t];
          X[2 * v + 1] = NP[2 * t + 1];
          F2[v] = 1;
          B2[v] = -1;
        });
  }
  st = std::move(nx);
  return c;
}

// What refinement hands back, in the executor's memory (report lists on the host).
struct Output {
  Buf<double> xy, attribute;
  Buf<std::int32_t> tri, nbr, seg, dup;
  std::int64_t np = 0, nt = 0, removed = 0;
  std::vector<std::int32_t> small, large;
  std::vector<std::int8_t> reasons;
  std::int64_t rounds = 0, splits = 0, points = 0, dropped = 0;
};

// The final round's mesh as the output: marks as base segments' final names (final_of_base:
// input segment or RefinedMesh2d::kHullSegment), region attributes as given, and the triangles
// left bad.
inline void finish(Exec& ex, State& st, cdt::DeviceResult& dr, const Subsegments& s,
                   const Decisions& d, const std::vector<std::int32_t>& final_of_base,
                   const Refine2dOptions& opt, Output& out) {
  const std::int64_t nt = dr.count;
  out.np = st.np;
  out.nt = nt;
  out.removed = dr.removed;
  out.xy = std::move(st.xy);
  out.tri = ex.template alloc<std::int32_t>(3 * std::size_t(std::max<std::int64_t>(nt, 1)));
  out.nbr = ex.template alloc<std::int32_t>(3 * std::size_t(std::max<std::int64_t>(nt, 1)));
  out.seg = ex.template alloc<std::int32_t>(3 * std::size_t(std::max<std::int64_t>(nt, 1)));
  out.dup = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(st.np, 1)));
  ex.copy(dr.triangles.get(), 3 * nt, out.tri.data());
  ex.copy(dr.neighbors.get(), 3 * nt, out.nbr.data());
  ex.copy(dr.duplicate_of.get(), st.np, out.dup.data());
  auto fob = ex.template alloc<std::int32_t>(std::max<std::size_t>(final_of_base.size(), 1));
  ex.from_host(final_of_base.data(), std::int64_t(final_of_base.size()), fob.data());
  {
    const std::int32_t *O = s.of_edge.data(), *SB = s.base.data(), *FB = fob.data();
    std::int32_t* G = out.seg.data();
    ex.for_each_index(
        3 * nt, GG_LAMBDA(std::int64_t e) { G[e] = O[e] < 0 ? -1 : FB[SB[O[e]]]; });
  }
  if (!opt.regions.empty()) {
    std::vector<double> attr;
    for (const auto& g : opt.regions) attr.push_back(g.attribute);
    auto da = ex.template alloc<double>(attr.size());
    ex.from_host(attr.data(), std::int64_t(attr.size()), da.data());
    out.attribute = ex.template alloc<double>(std::size_t(std::max<std::int64_t>(nt, 1)));
    const double *A = dr.attribute.get(), *DA = da.data();
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

// The hull's boundary edges on no segment, as new base segments and subsegments (Triangle's
// -c: without Domain::Enclosed the convex hull bounds the mesh).
inline void add_boundary(Exec& ex, State& st, const RoundMesh& m, std::vector<std::int32_t>& base,
                         std::vector<std::int32_t>& final_of_base) {
  std::vector<std::int32_t> tri(3 * std::size_t(m.nt)), nbr(3 * std::size_t(m.nt)),
      seg(3 * std::size_t(m.nt));
  ex.to_host(m.tri, 3 * m.nt, tri.data());
  ex.to_host(m.nbr, 3 * m.nt, nbr.data());
  ex.to_host(m.seg, 3 * m.nt, seg.data());
  std::vector<std::int32_t> segs(2 * std::size_t(st.ns)), sb(std::size_t(st.ns));
  ex.to_host(st.segs.data(), 2 * st.ns, segs.data());
  ex.to_host(st.seg_base.data(), st.ns, sb.data());
  for (std::size_t e = 0; e < tri.size(); ++e) {
    if (nbr[e] >= 0 || seg[e] >= 0) continue;
    const std::size_t t = e / 3, k = e % 3;
    const std::int32_t a = tri[3 * t + (k + 1) % 3], b = tri[3 * t + (k + 2) % 3];
    sb.push_back(std::int32_t(base.size() / 2));
    base.insert(base.end(), {a, b});
    final_of_base.push_back(RefinedMesh2d::kHullSegment);
    segs.insert(segs.end(), {a, b});
  }
  st.ns = std::int64_t(sb.size());
  st.segs = ex.template alloc<std::int32_t>(std::max<std::size_t>(segs.size(), 2));
  st.seg_base = ex.template alloc<std::int32_t>(std::max<std::size_t>(sb.size(), 1));
  ex.from_host(segs.data(), std::int64_t(segs.size()), st.segs.data());
  ex.from_host(sb.data(), std::int64_t(sb.size()), st.seg_base.data());
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
  State st;
  st.np = n;
  st.ns = nseg;
  st.xy = ex.template alloc<double>(2 * std::size_t(std::max<std::int64_t>(n, 1)));
  ex.copy(xy, 2 * n, st.xy.data());
  st.free_pt = ex.template alloc<std::int8_t>(std::size_t(std::max<std::int64_t>(n, 1)));
  st.on_base = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(n, 1)));
  ex.fill(st.free_pt.data(), n, std::int8_t(0));
  ex.fill(st.on_base.data(), n, std::int32_t(-1));
  st.segs = ex.template alloc<std::int32_t>(2 * std::size_t(std::max<std::int64_t>(nseg, 1)));
  ex.copy(segs, 2 * nseg, st.segs.data());
  st.seg_base = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(nseg, 1)));
  {
    std::int32_t* SB = st.seg_base.data();
    ex.for_each_index(
        nseg, GG_LAMBDA(std::int64_t j) { SB[j] = std::int32_t(j); });
  }
  std::vector<std::int32_t> base(2 * std::size_t(nseg));
  ex.to_host(segs, 2 * nseg, base.data());

  Cdt2dOptions copt;
  static_cast<RunOptions&>(copt) = opt;
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
  bool hull = opt.domain == Cdt2dOptions::Domain::ConvexHull, last = !bounded;
  Buf<std::int8_t> corner;
  Buf<std::int32_t> dbase;
  constexpr std::int64_t kStall = 64;
  double best_share = 2;
  std::int64_t best_round = 0;
  bool stalled = false;
  for (std::int64_t round = 0;; ++round) {
    cdt::DeviceResult dr;
    Stats cst;
    rc = {};
    cdt_impl::triangulate_device(st.xy.data(), st.np, st.segs.data(), st.ns, copt, dr, cst, rc);
    if (rc.cross_a >= 0) return;
    const RoundMesh m{st.xy.data(),
                      dr.triangles.get(),
                      dr.neighbors.get(),
                      dr.segment_of.get(),
                      dr.duplicate_of.get(),
                      dr.attribute.get(),
                      dr.count};
    if (hull) {
      // Once: the hull's edges become segments, and the mesh is the domain they enclose.
      add_boundary(ex, st, m, base, final_of_base);
      copt.domain = Cdt2dOptions::Domain::Enclosed;
      hull = false;
      continue;
    }
    if (!corner.size()) {
      dbase = ex.template alloc<std::int32_t>(std::max<std::size_t>(base.size(), 2));
      ex.from_host(base.data(), std::int64_t(base.size()), dbase.data());
      const std::vector<std::int8_t> c = corner_kinds(ex, xy, n, base);
      corner = ex.template alloc<std::int8_t>(std::max<std::size_t>(c.size(), 1));
      ex.from_host(c.data(), std::int64_t(c.size()), corner.data());
    }
    const Subsegments s = subsegments_of(ex, m, st.seg_base.data());
    Decisions d;
    d.split = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(s.count, 1)));
    d.drop = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(st.np, 1)));
    const std::size_t tn = std::size_t(std::max<std::int64_t>(m.nt, 1));
    d.point = ex.template alloc<double>(2 * tn);
    d.land = ex.template alloc<std::int32_t>(tn);
    d.key = ex.template alloc<std::uint64_t>(tn);
    d.reason = ex.template alloc<std::int8_t>(tn);
    d.large = ex.template alloc<std::int8_t>(tn);
    ex.fill(d.split.data(), s.count, std::int32_t(0));
    ex.fill(d.drop.data(), st.np, std::int32_t(0));
    Buf<double> sizes;
    Bounds b = bounds;
    if (opt.max_area_at) {
      host_sizes(ex, m, st.np, opt.max_area_at, sizes);
      b.triangle_area = sizes.data();
    }
    find_encroached(ex, m, s, st.free_pt.data(), bounds.lens, d);
    const Terminator tm{st.on_base.data(), dbase.data(), corner.data(), n};
    find_bad(ex, m, s, b, tm, Corners{corner.data(), n}, d);
    Buf<std::int32_t> winners;
    const std::int64_t nwin = choose_points(ex, m, s, d, winners);
    auto any = ex.template alloc<std::int64_t>(2);
    std::int64_t flagged = 0;
    if (!last) {
      const std::int32_t *SP = d.split.data(), *DR = d.drop.data();
      const std::int64_t ns = s.count;
      ex.transform_reduce_into(
          ns + st.np,
          GG_LAMBDA(std::int64_t i)->std::int64_t { return i < ns ? SP[i] : DR[i - ns]; },
          std::int64_t(0), thrust::plus<std::int64_t>(), any.data());
      // The bad triangles refinement still works on (the terminator's excepted).
      const std::int8_t *R = d.reason.data(), *LG = d.large.data();
      ex.transform_reduce_into(
          m.nt,
          GG_LAMBDA(std::int64_t t)->std::int64_t {
            return R[t] == std::int8_t(SmallAngle::Limit) || LG[t] ? 1 : 0;
          },
          std::int64_t(0), thrust::plus<std::int64_t>(), any.data() + 1);
      std::int64_t h[2];
      ex.to_host(any.data(), 2, h);
      flagged = h[0];
      // Refinement whose share of bad triangles has not fallen for kStall rounds has stalled
      // (near the angle limit new points can make bad triangles as fast as they remove them):
      // it stops, the bad triangles reported as Limit, rather than run on without end. (The
      // share, not the count: refining to an area bound multiplies the large triangles for many
      // rounds before their number falls.)
      const double share = double(h[1]) / double(std::max<std::int64_t>(m.nt, 1));
      if (share < best_share) best_share = share, best_round = round;
      if (round - best_round > kStall) stalled = true;
    }
    if (last || stalled || (flagged == 0 && nwin == 0)) {
      out.rounds = round + 1;
      finish(ex, st, dr, s, d, final_of_base, opt, out);
      return;
    }
    const Counts c =
        build_next(ex, st, m, s, d, winners, nwin, corner.data(), n, opt.max_steiner_points);
    out.splits += c.splits;
    out.points += c.points;
    out.dropped += c.dropped;
    // Nothing could be added or removed (the Steiner limit, or no double where points belong):
    // one more triangulation is the mesh.
    if (c.splits + c.points + c.dropped == 0 ||
        (opt.max_steiner_points >= 0 && st.np - n >= opt.max_steiner_points))
      last = true;
  }
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
  const OutBuffer<double> nod;
  const OutBuffer<std::int32_t> noi;
  deliver::to_host(ex, o.xy.data(), 2 * o.np, nod, r.points);
  deliver::to_host(ex, o.tri.data(), 3 * o.nt, noi, r.triangles);
  deliver::to_host(ex, o.nbr.data(), 3 * o.nt, noi, r.neighbors);
  deliver::to_host(ex, o.seg.data(), 3 * o.nt, noi, r.segment_of);
  deliver::to_host(ex, o.dup.data(), o.np, noi, r.duplicate_of);
  if (!opt.regions.empty()) deliver::to_host(ex, o.attribute.data(), o.nt, nod, r.attribute);
  r.stats.phase_ms.push_back({"to_host", ms_since(t1)});
  r.small_angles.assign(o.small.begin(), o.small.end());
  r.small_angle_reasons.assign(o.reasons.begin(), o.reasons.end());
  r.large_triangles.assign(o.large.begin(), o.large.end());
  r.removed_triangles = o.removed;
  tally = {o.rounds, o.splits, o.points, o.dropped};
}

// Executor memory in (segment indices checked there), executor memory out.
inline void refine_device_impl(const double* xy, std::int64_t n, const std::int32_t* segs,
                               std::int64_t nseg, const Refine2dOptions& opt, DeviceResult& d,
                               cdt::RecoveryCounts& rc, Tally& tally) {
  Exec ex(opt);
  check_segment_indices(ex, segs, nseg, n);
  std::vector<std::int32_t> final_of_base(static_cast<std::size_t>(nseg));
  for (std::int64_t j = 0; j < nseg; ++j) final_of_base[std::size_t(j)] = std::int32_t(j);
  Output o;
  refine_core(ex, xy, n, segs, nseg, final_of_base, opt, o, rc);
  if (rc.cross_a >= 0) return;
  ex.sync();
  d.np = o.np, d.nt = o.nt, d.removed = o.removed;
  d.xy = o.xy.hand_over();
  d.tri = o.tri.hand_over();
  d.nbr = o.nbr.hand_over();
  d.seg = o.seg.hand_over();
  d.dup = o.dup.hand_over();
  if (!opt.regions.empty()) d.attribute = o.attribute.hand_over();
  d.small = std::move(o.small);
  d.large = std::move(o.large);
  d.reasons = std::move(o.reasons);
  tally = {o.rounds, o.splits, o.points, o.dropped};
}
