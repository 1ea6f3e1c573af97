// delaunay3d_devices' frame (del3d_backend.hpp: assemble_blocks), on the CPU executor only
// (included by del3d_cpu.cpp): the points prepared as a single call prepares them (the checks,
// the duplicates, the curve), the blocks run, and their owned tetrahedra put in the single
// call's order with its vertex map and hull facets, so the arrays are the single call's.

inline void assemble_impl(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                          const BlocksFn& blocks, Output& out) {
  Delaunay3dStats& st = out.stats;
  Exec ex(opt);
  Prepared P = prepare_points(ex, xyz, n, false, st);
  mesh::SortedPoints<Exec>& S = P.S;
  blocks_detail::OwnedBlocks B = blocks(st);
  const auto t0 = Clock::now();
  auto rank = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* rk = rank.data();
  const std::int32_t* orig = S.orig.data();
  ex.for_each_index(
      S.m, GG_LAMBDA(std::int64_t w) { rk[orig[w]] = std::int32_t(w); });
  std::vector<const std::int64_t*> s, nb;
  for (std::size_t b = 0; b < B.simplices.size(); ++b)
    s.push_back(B.simplices[b].data()), nb.push_back(B.neighbors[b].data());
  using Store = blocks_detail::OwnedStore<4, mesh::SimplexRecord<4>>;
  const Store store{s.data(), nb.data(), B.offsets.data(), int(s.size()), rk};
  auto f = mesh::compact_live_sorted<4>(ex, B.offsets.back(), store, S.m,
                                        host_arrays(opt.into, out), /*with_last=*/true);
  B = {};
  to_output(ex, S, f, n, opt.into, out);
  st.phase_ms.push_back({"output", ms_since(t0)});
}
