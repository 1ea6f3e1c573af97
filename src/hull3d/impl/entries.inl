// The 3D hull's entries on one executor (hull3d_backend.hpp's Entries; exec/dispatch.hpp),
// included after unit.inl by each executor's unit (hull3d_cpu.cpp, hull3d_cuda.cu).
constexpr auto make_kept = &::gpugeom::detail::make_kept_on<Kept, KeptHullOn, Exec, Hull3dOptions>;
const Entries entries{make_kept, &compute_impl, &compute_device_impl};
