// 2D Delaunay's entries on one executor (del2d_backend.hpp's Entries; exec/dispatch.hpp), included
// after unit.inl by the library's unit for each executor (del2d_cpu.cpp, del2d_cuda.cu).
inline std::unique_ptr<Kept> make_kept(const Delaunay2dOptions& opt) {
  return std::make_unique<KeptOn>(Exec::kept_options(opt));
}
const Entries entries{{&make_kept, &triangulate_impl, &triangulate_device_impl},
                      &triangulate_digital_impl};
