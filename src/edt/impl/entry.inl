// The entry points edt_backend.hpp and edt_device.hpp declare, the same for both executors: an
// N-D grid (4 to 8 axes) runs nd.inl's passes for its index width; a whole 2D / 3D grid runs the
// passes compiled for the request's site packing (run.inl, included once for each in namespaces
// bits and linear), slices theirs by blocks (slices.inl, once for each block layout).

void run(const Request& req, Output& out, EdtStats& stats) {
  if (req.nd.nd && !req.slices.empty() && req.nd.wide)
    nd64::run_nd_slices(req, out, stats);
  else if (req.nd.nd && !req.slices.empty())
    nd32::run_nd_slices(req, out, stats);
  else if (req.nd.nd && req.nd.wide)
    nd64::run_nd(req, out, stats);
  else if (req.nd.nd)
    nd32::run_nd(req, out, stats);
  else if (!req.slices.empty() && req.layout.columns)
    column_slices::run_slices(req, out, stats);
  else if (!req.slices.empty() && req.layout.linear)
    linear_slices::run_slices(req, out, stats);
  else if (!req.slices.empty())
    bits_slices::run_slices(req, out, stats);
  else if (req.layout.linear)
    linear::run_whole(req, out, stats);
  else
    bits::run_whole(req, out, stats);
}
// Modules built on the transform (cvd/, the Delaunay modules' digital methods) hold bit-packed
// sites (make_layout with Packing::Bits): their own code decodes them. They call with their own
// executor; the transform runs on one of this unit's type bound to the same device and stream
// (each CUDA unit's executor type is its own: exec/tu_exec.hpp).
using HeldExec = std::conditional_t<Exec::backend == Backend::Cuda, CudaExec, CpuExec>;
template <class E>
RunOptions held_place(const E& e) {
  RunOptions r;
  r.backend = E::backend;
  if constexpr (E::backend == Backend::Cuda) {
    r.device = e.device();
    r.stream = e.stream();
  }
  return r;
}
void feature_transform_held(HeldExec& caller, const Layout& L, const Metric& M, std::uint32_t* feat,
                            std::int64_t sites) {
  Exec ex(held_place(caller));
  bits::feature_transform(ex, L, M, feat, nullptr, Tuning{}, sites, nullptr);
}

// Every column's first and last site of a grid on the executor (BoundsRequest): a thread per
// column walks it through the planes, so that a warp reads consecutive columns of a plane.
template <class T>
void bounds_sweep(Exec& ex, const BoundsRequest& rq, std::int64_t* lo, std::int64_t* hi,
                  std::uint32_t* nan) {
  const T* g = static_cast<const T*>(rq.grid);
  const std::int64_t planes = rq.planes, plane = rq.plane, offset = rq.offset;
  const bool nonzero = rq.rule == SiteRule::NonZero;
  ex.for_each_index(
      plane, GG_LAMBDA(std::int64_t c) {
        std::int64_t f = -1, l = -1;
        bool bad = false;
        for (std::int64_t z = 0; z < planes; ++z) {
          const T v = g[z * plane + c];
          if constexpr (std::is_floating_point_v<T>) bad |= v != v;
          if ((v != T(0)) == nonzero) {
            if (f < 0) f = z + offset;
            l = z + offset;
          }
        }
        lo[c] = f;
        hi[c] = l;
        if (bad) nan[0] = 1;  // (every writer writes 1)
      });
}

bool column_bounds(const BoundsRequest& rq, std::int64_t* first, std::int64_t* last) {
  Exec ex(rq.run);
  auto lo = ex.template alloc<std::int64_t>(std::size_t(rq.plane));
  auto hi = ex.template alloc<std::int64_t>(std::size_t(rq.plane));
  auto nan = ex.template alloc<std::uint32_t>(1);
  ex.fill(nan.data(), 1, std::uint32_t(0));
  grid_input::visit(rq.type, [&](auto tag) {
    bounds_sweep<decltype(tag)>(ex, rq, lo.data(), hi.data(), nan.data());
  });
  ex.to_host(lo.data(), rq.plane, first);
  ex.to_host(hi.data(), rq.plane, last);
  std::uint32_t h = 0;
  ex.to_host(nan.data(), 1, &h);
  return h != 0;
}

const Entries entries{&run, &column_bounds};
