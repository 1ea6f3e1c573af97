// 2D Delaunay's entries on one executor (del2d_backend.hpp's Entries; exec/dispatch.hpp), included
// after unit.inl by the library's unit for each executor (del2d_cpu.cpp, del2d_cuda.cu).
inline std::unique_ptr<Kept> make_kept(const RunOptions& run) {
  return std::make_unique<KeptOn>(Exec::kept_options(run));
}
const Entries entries{&make_kept, &triangulate_impl, &triangulate_digital_impl,
                      &triangulate_device_impl};
