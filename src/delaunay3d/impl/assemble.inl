// delaunay3d_devices' frame (del3d_backend.hpp: assemble_blocks), on either executor: the
// points prepared as a single call prepares them (the checks, the duplicates, the curve), the
// blocks run, and their owned tetrahedra put in the single call's order with its vertex map and
// hull facets, so the arrays are the single call's. On the GPU this is the single call's own
// output step, on the first device, around the blocks.

inline void assemble_impl(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                          const BlocksFn& blocks, Output& out) {
  Delaunay3dStats& st = out.stats;
  Exec ex(opt);
  Prepared P = prepare_points(ex, xyz, n, false, st);
  mesh::SortedPoints<Exec>& S = P.S;
  // (the blocks' split made here, where the points are: blocks/split_on.hpp)
  blocks_detail::PreparedPoints view;
  view.m = S.m;
  view.pts = S.pts.data();
  view.bounds = blocks_detail::points_bounds<3>(P.box);
  view.split = [&](const blocks_detail::SplitLayout& layout) {
    return blocks_detail::split_on<3>(ex, S.pts.data(), S.orig.data(), S.m, layout);
  };
  view.hull = [&] { return blocks_detail::hull_vertices_on(ex, S.pts.data(), S.m, opt); };
  blocks_detail::OwnedBlocks B = blocks(st, view);
  const auto t0 = Clock::now();
  {
    auto o = blocks_detail::owned_on<4>(ex, B, S.orig.data(), S.m, n);
    B = {};  // (copied: the blocks' rows freed)
    auto f = mesh::compact_live_sorted<4>(ex, o.count, o.store, S.m, host_arrays(opt.into, out),
                                          /*with_last=*/true);
    o = {};
    to_output(ex, S, f, n, opt.into, out);
  }
  st.phase_ms.push_back({"output", ms_since(t0)});
}

inline void assemble_entry(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                           const BlocksFn& blocks, Output& out) {
  out.stats.backend = Exec::backend;
  assemble_impl(xyz, n, opt, blocks, out);
}

// One block of the several devices (blocks/block_pass.hpp): triangulated on opt's device by the
// device entry, and its passes there.
inline void block_entry(const Delaunay3dOptions& opt, const blocks_detail::BlockTask& t,
                        const blocks_detail::FinalTest& test, blocks_detail::BlockRows& out) {
  Exec ex(opt);
  blocks_detail::run_block<3>(
      ex, t, test, out, [&](const double* p, const ::gpugeom::detail::ExecContext* ctx) {
        DeviceOutput r;
        Delaunay3dStats st;
        triangulate_device_impl(p, t.n, opt, r, st, ctx);
        return blocks_detail::DeviceSimplices{r.tetrahedra, r.neighbors, r.num_tetrahedra};
      });
}

const Assembly assembly{&assemble_entry, &block_entry};
