// Public entry of DynamicDelaunay2d (issue 47): checks, the executor, the kept state's results.
#include <string>

#include "delaunay2d/del2d_backend.hpp"
#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "exec/dynamic_state.hpp"
#include "gpugeom/delaunay2d.hpp"

namespace gpugeom {

struct DynamicDelaunay2d::Impl : detail::DynamicState<del2d::Kept> {
  void insert(const double* xy, std::int64_t n, bool on_device) {
    DynamicState::insert(xy, n, on_device, [](std::int64_t total) { del2d::check_count(total); });
  }
};

namespace {
void refuse_options(const Delaunay2dOptions& opt) {
  if (opt.method == Method::Digital)
    throw Error(ErrorCode::Unsupported,
                "DynamicDelaunay2d: Method::Digital is not offered (Method::Incremental gives "
                "the same triangulation)");
  if (opt.into.triangles || opt.into.neighbors || opt.into.duplicate_of)
    throw Error(ErrorCode::Unsupported,
                "DynamicDelaunay2d: opt.into is not used; read the results with triangulation() "
                "or device_triangulation()");
}
}  // namespace

DynamicDelaunay2d::DynamicDelaunay2d(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

DynamicDelaunay2d::DynamicDelaunay2d(const double* xy, std::int64_t n,
                                     const Delaunay2dOptions& opt) {
  refuse_options(opt);
  del2d::check_count(n);
  auto impl = std::make_unique<Impl>();
  impl->backend = resolve_backend(opt.backend, opt.device);
  impl->kept = GG_ENTRIES(impl->backend, del2d).make_kept(opt);
  impl->insert(xy, n, false);
  impl_ = std::move(impl);
}

DynamicDelaunay2d DynamicDelaunay2d::from_device(const double* device_xy, std::int64_t n,
                                                 const Delaunay2dOptions& opt) {
  refuse_options(opt);
  del2d::check_count(n);
  auto impl = std::make_unique<Impl>();
  impl->backend = device_entry_backend(opt.backend, opt.device, "DynamicDelaunay2d::from_device");
  impl->kept = GG_ENTRIES(impl->backend, del2d).make_kept(opt);
  impl->insert(device_xy, n, true);
  return DynamicDelaunay2d(std::move(impl));
}

DynamicDelaunay2d::DynamicDelaunay2d(DynamicDelaunay2d&&) noexcept = default;
DynamicDelaunay2d& DynamicDelaunay2d::operator=(DynamicDelaunay2d&&) noexcept = default;
DynamicDelaunay2d::~DynamicDelaunay2d() = default;

void DynamicDelaunay2d::insert(const double* xy, std::int64_t n) {
  impl_->insert(xy, n, false);
}
void DynamicDelaunay2d::insert_device(const double* device_xy, std::int64_t n) {
  impl_->insert(device_xy, n, impl_->backend == Backend::Cuda);
}
void DynamicDelaunay2d::move(const double* xy, std::int64_t n) {
  impl_->move(xy, n, false);
}
void DynamicDelaunay2d::move_device(const double* device_xy, std::int64_t n) {
  impl_->move(device_xy, n, impl_->backend == Backend::Cuda);
}

void DynamicDelaunay2d::remove(const std::int32_t* indices, std::int64_t count) {
  impl_->remove(indices, count, false);
}
void DynamicDelaunay2d::remove_device(const std::int32_t* device_indices, std::int64_t count) {
  impl_->remove(device_indices, count, impl_->backend == Backend::Cuda);
}
std::int64_t DynamicDelaunay2d::num_removed() const {
  return impl_->kept->removed();
}

std::int64_t DynamicDelaunay2d::num_points() const {
  return impl_->kept->points();
}
std::int64_t DynamicDelaunay2d::num_triangles() const {
  return impl_->kept->simplices();
}
std::int64_t DynamicDelaunay2d::num_duplicates() const {
  return impl_->kept->duplicates();
}
Backend DynamicDelaunay2d::backend() const {
  return impl_->backend;
}
void DynamicDelaunay2d::track_changes(bool on) {
  impl_->kept->track_changes(on);
}
SimplexChanges DynamicDelaunay2d::changes() const {
  return impl_->changes("DynamicDelaunay2d");
}
DeviceSimplexChanges DynamicDelaunay2d::device_changes() const {
  return impl_->device_changes("DynamicDelaunay2d");
}
const Stats& DynamicDelaunay2d::stats() const {
  return impl_->stats;
}

Triangulation2d DynamicDelaunay2d::triangulation() const {
  Triangulation2d r;
  impl_->kept->host_copy(r);
  r.stats = impl_->stats;
  return r;
}

DeviceTriangulation2d DynamicDelaunay2d::device_triangulation() const {
  DeviceTriangulation2d r;
  impl_->kept->device_copy(r);
  r.num_points = impl_->kept->points();
  r.backend = impl_->backend;
  r.stats = impl_->stats;
  return r;
}

}  // namespace gpugeom
