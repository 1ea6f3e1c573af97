// delaunay2d_devices' frame (del2d_backend.hpp: assemble_blocks), on the CPU executor only
// (included by del2d_cpu.cpp): the points prepared as a single call prepares them (the checks,
// the duplicates, the curve), the blocks run, and their owned triangles put in the single call's
// order, so the arrays are the single call's.

inline void assemble_impl(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                          const BlocksFn& blocks, Output& out) {
  Delaunay2dStats& st = out.stats;
  Exec ex(opt);
  auto t0 = Clock::now();
  Prepared P = prepare(ex, xy, n, false);
  st.points = n;
  st.distinct_points = P.m;
  st.duplicates = P.duplicates;
  st.phase_ms.push_back({"prepare", ms_since(t0)});
  blocks_detail::OwnedBlocks B = blocks(st);
  t0 = Clock::now();
  auto rank = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* rk = rank.data();
  const std::int32_t* orig = P.orig.data();
  ex.for_each_index(
      P.m, GG_LAMBDA(std::int64_t w) { rk[orig[w]] = std::int32_t(w); });
  std::vector<const std::int64_t*> s, nb;
  for (std::size_t b = 0; b < B.simplices.size(); ++b)
    s.push_back(B.simplices[b].data()), nb.push_back(B.neighbors[b].data());
  using Store = blocks_detail::OwnedStore<3, mesh::SimplexRecord<3>>;
  const Store store{s.data(), nb.data(), B.offsets.data(), int(s.size()), rk};
  auto f = mesh::compact_live_sorted<3>(
      ex, B.offsets.back(), store, P.m,
      mesh::IntoResult<3, Exec, decltype(out.triangles)>{
          bool(opt.into.triangles) || bool(opt.into.neighbors), out.triangles, out.neighbors});
  B = {};
  detail::Prefault pf;  // (nothing to fault in: the CPU executor wrote the host arrays)
  deliver_host_results(ex, opt.into, n, P, f, out, st, pf);
  st.phase_ms.push_back({"output", ms_since(t0)});
}
