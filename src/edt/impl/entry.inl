// The entry points edt_backend.hpp and edt_device.hpp declare, the same for both executors: an
// N-D grid (4 to 8 axes) runs nd.inl's passes for its index width; a whole 2D / 3D grid runs the
// passes compiled for the request's site packing (run.inl, included once for each in namespaces
// bits and linear), slices theirs by blocks (slices.inl, once for each block layout).

void run(const Request& req, Output& out, Stats& stats) {
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
