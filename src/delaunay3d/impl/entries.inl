// 3D Delaunay's entries on one executor (del3d_backend.hpp's Entries; exec/dispatch.hpp), included
// after unit.inl by the library's unit for each executor (del3d_cpu.cpp, del3d_cuda.cu).
inline std::unique_ptr<Kept> make_kept(const Delaunay3dOptions& opt) {
  return std::make_unique<KeptOn>(Exec::kept_options(opt));
}
const Entries entries{&make_kept, &triangulate_impl, &triangulate_device_impl};
