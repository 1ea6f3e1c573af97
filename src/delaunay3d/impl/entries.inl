// 3D Delaunay's entries on one executor (del3d_backend.hpp's Entries; exec/dispatch.hpp), included
// after unit.inl by the library's unit for each executor (del3d_cpu.cpp, del3d_cuda.cu).
constexpr auto make_kept = &::gpugeom::detail::make_kept_on<Kept, KeptOn, Exec, Delaunay3dOptions>;
const Entries entries{make_kept, &triangulate_impl, &triangulate_device_impl};
