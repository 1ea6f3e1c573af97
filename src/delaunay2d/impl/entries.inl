// 2D Delaunay's entries on one executor (del2d_backend.hpp's Entries; exec/dispatch.hpp), included
// after unit.inl by the library's unit for each executor (del2d_cpu.cpp, del2d_cuda.cu).
constexpr auto make_kept = &::gpugeom::detail::make_kept_on<Kept, KeptOn, Exec, Delaunay2dOptions>;
const Entries entries{{make_kept, &triangulate_impl, &triangulate_device_impl},
                      &triangulate_digital_impl};
