// delaunay2d_devices' frame (del2d_backend.hpp: assemble_blocks), on either executor: the
// points prepared as a single call prepares them (the checks, the duplicates, the curve), the
// blocks run, and their owned triangles put in the single call's order, so the arrays are the
// single call's. On the GPU this is the single call's own output step, on the first device,
// around the blocks (the result's pages faulted in meanwhile, as a single call does).

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
  detail::Prefault pf;
  size_host_results(opt.into, n, P, out, pf);
  // (the blocks' split made here, where the points are: blocks/split_on.hpp)
  blocks_detail::PreparedPoints view;
  view.m = P.m;
  view.pts = P.pts.data();
  view.bounds = blocks_detail::points_bounds<2>(P.box);
  view.split = [&](const blocks_detail::SplitLayout& layout) {
    return blocks_detail::split_on<2>(ex, P.pts.data(), P.orig.data(), P.m, layout);
  };
  view.hull = [&] { return blocks_detail::hull_filter_on(ex, P.pts.data(), P.m); };
  blocks_detail::OwnedBlocks B = blocks(st, view);
  t0 = Clock::now();
  {
    auto o = blocks_detail::owned_on<3>(ex, B, P.orig.data(), P.m, n);
    B = {};  // (copied: the blocks' rows freed)
    auto f = mesh::compact_live_sorted<3>(
        ex, o.count, o.store, P.m,
        mesh::IntoResult<3, Exec, decltype(out.triangles)>{
            bool(opt.into.triangles) || bool(opt.into.neighbors), out.triangles, out.neighbors});
    o = {};
    deliver_host_results(ex, opt.into, n, P, f, out, st, pf);
  }
  st.phase_ms.push_back({"output", ms_since(t0)});
}

inline void assemble_entry(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                           const BlocksFn& blocks, Output& out) {
  out.stats.backend = Exec::backend;
  assemble_impl(xy, n, opt, blocks, out);
}

// One block of the several devices (blocks/block_pass.hpp): triangulated on opt's device by the
// device entry, and its passes there.
inline void block_entry(const Delaunay2dOptions& opt, const blocks_detail::BlockTask& t,
                        const blocks_detail::FinalTest& test, blocks_detail::BlockRows& out) {
  Exec ex(opt);
  blocks_detail::run_block<2>(
      ex, t, test, out, [&](const double* p, const ::gpugeom::detail::ExecContext* ctx) {
        DeviceOutput r;
        Delaunay2dStats st;
        triangulate_device_impl(p, t.n, opt, r, st, ctx);
        return blocks_detail::DeviceSimplices{r.triangles, r.neighbors, r.num_triangles};
      });
}

const Assembly assembly{&assemble_entry, &block_entry};
