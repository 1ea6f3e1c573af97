// Public entry of DynamicDelaunay3d (issue 47): checks, the executor, the kept state's results.
#include <string>

#include "delaunay3d/del3d_backend.hpp"
#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "exec/dynamic_state.hpp"
#include "gpugeom/delaunay3d.hpp"

namespace gpugeom {

struct DynamicDelaunay3d::Impl : detail::DynamicState<del3d::Kept> {
  void insert(const double* xyz, std::int64_t n, bool on_device) {
    DynamicState::insert(xyz, n, on_device, [](std::int64_t total) { del3d::check_count(total); });
  }
};

namespace {
void refuse_options(const Delaunay3dOptions& opt) {
  if (opt.method == Method::Digital)
    throw Error(ErrorCode::Unsupported,
                "DynamicDelaunay3d: Method::Digital is not offered (Method::Incremental gives "
                "the same tetrahedra)");
  const Triangulation3dBuffers& i = opt.into;
  if (i.tetrahedra || i.neighbors || i.duplicate_of || i.vertex_to_simplex || i.hull_facets)
    throw Error(ErrorCode::Unsupported,
                "DynamicDelaunay3d: opt.into is not used; read the results with "
                "tetrahedralisation() or device_tetrahedralisation()");
}

}  // namespace

DynamicDelaunay3d::DynamicDelaunay3d(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

DynamicDelaunay3d::DynamicDelaunay3d(const double* xyz, std::int64_t n,
                                     const Delaunay3dOptions& opt) {
  refuse_options(opt);
  del3d::check_count(n);
  auto impl = std::make_unique<Impl>();
  impl->backend = resolve_backend(opt.backend, opt.device);
  impl->kept = GG_ENTRIES(impl->backend, del3d).make_kept(opt);
  impl->insert(xyz, n, false);
  impl_ = std::move(impl);
}

DynamicDelaunay3d DynamicDelaunay3d::from_device(const double* device_xyz, std::int64_t n,
                                                 const Delaunay3dOptions& opt) {
  refuse_options(opt);
  del3d::check_count(n);
  auto impl = std::make_unique<Impl>();
  impl->backend = device_entry_backend(opt.backend, opt.device, "DynamicDelaunay3d::from_device");
  impl->kept = GG_ENTRIES(impl->backend, del3d).make_kept(opt);
  impl->insert(device_xyz, n, true);
  return DynamicDelaunay3d(std::move(impl));
}

DynamicDelaunay3d::DynamicDelaunay3d(DynamicDelaunay3d&&) noexcept = default;
DynamicDelaunay3d& DynamicDelaunay3d::operator=(DynamicDelaunay3d&&) noexcept = default;
DynamicDelaunay3d::~DynamicDelaunay3d() = default;

void DynamicDelaunay3d::insert(const double* xyz, std::int64_t n) {
  impl_->insert(xyz, n, false);
}
void DynamicDelaunay3d::insert_device(const double* device_xyz, std::int64_t n) {
  impl_->insert(device_xyz, n, impl_->backend == Backend::Cuda);
}
void DynamicDelaunay3d::move(const double* xyz, std::int64_t n) {
  impl_->move(xyz, n, false);
}
void DynamicDelaunay3d::move_device(const double* device_xyz, std::int64_t n) {
  impl_->move(device_xyz, n, impl_->backend == Backend::Cuda);
}

void DynamicDelaunay3d::remove(const std::int32_t* indices, std::int64_t count) {
  impl_->remove(indices, count, false);
}
void DynamicDelaunay3d::remove_device(const std::int32_t* device_indices, std::int64_t count) {
  impl_->remove(device_indices, count, impl_->backend == Backend::Cuda);
}
std::int64_t DynamicDelaunay3d::num_removed() const {
  return impl_->kept->removed();
}

std::int64_t DynamicDelaunay3d::num_points() const {
  return impl_->kept->points();
}
std::int64_t DynamicDelaunay3d::num_tetrahedra() const {
  return impl_->kept->simplices();
}
std::int64_t DynamicDelaunay3d::num_duplicates() const {
  return impl_->kept->duplicates();
}
Backend DynamicDelaunay3d::backend() const {
  return impl_->backend;
}
void DynamicDelaunay3d::track_changes(bool on) {
  impl_->kept->track_changes(on);
}
SimplexChanges DynamicDelaunay3d::changes() const {
  return impl_->changes("DynamicDelaunay3d");
}
DeviceSimplexChanges DynamicDelaunay3d::device_changes() const {
  return impl_->device_changes("DynamicDelaunay3d");
}
const Stats& DynamicDelaunay3d::stats() const {
  return impl_->stats;
}

Triangulation3d DynamicDelaunay3d::tetrahedralisation() const {
  Triangulation3d r;
  impl_->kept->host_copy(r);
  r.stats = impl_->stats;
  return r;
}

DeviceTriangulation3d DynamicDelaunay3d::device_tetrahedralisation() const {
  DeviceTriangulation3d r;
  impl_->kept->device_copy(r);
  r.num_points = impl_->kept->points();
  r.backend = impl_->backend;
  r.stats = impl_->stats;
  return r;
}

}  // namespace gpugeom
