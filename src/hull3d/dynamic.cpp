// Public entry of DynamicHull3d (issue 47): checks, the executor, the kept state's results.
#include <string>

#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "exec/dynamic_state.hpp"
#include "gpugeom/hull3d.hpp"
#include "hull3d/hull3d_backend.hpp"

namespace gpugeom {

struct DynamicHull3d::Impl : detail::DynamicState<hull3d::Kept> {
  void insert(const double* xyz, std::int64_t n, bool on_device) {
    DynamicState::insert(xyz, n, on_device, [](std::int64_t total) { hull3d::check_count(total); });
  }
  template <class Result>
  Result with_stats(Result r) const {
    r.stats = stats;
    return r;
  }
};

namespace {
void refuse_options(const Hull3dOptions& opt) {
  const Hull3dBuffers& i = opt.into;
  if (i.triangles || i.neighbors || i.vertices || i.equations)
    throw Error(ErrorCode::Unsupported,
                "DynamicHull3d: opt.into is not used; read the results with hull() or "
                "device_hull()");
}

// (Impl is private: named by the members that call this)
template <class Impl>
std::unique_ptr<Impl> start(const Hull3dOptions& opt, std::int64_t n, Backend b) {
  refuse_options(opt);
  hull3d::check_count(n);
  auto impl = std::make_unique<Impl>();
  impl->backend = b;
  impl->kept = GG_ENTRIES(b, hull3d).make_kept(opt);
  return impl;
}
}  // namespace

DynamicHull3d::DynamicHull3d(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

DynamicHull3d::DynamicHull3d(const double* xyz, std::int64_t n, const Hull3dOptions& opt)
    : impl_(start<Impl>(opt, n, resolve_backend(opt.backend, opt.device))) {
  impl_->insert(xyz, n, false);
}

DynamicHull3d DynamicHull3d::from_device(const double* device_xyz, std::int64_t n,
                                         const Hull3dOptions& opt) {
  auto impl = start<Impl>(
      opt, n, device_entry_backend(opt.backend, opt.device, "DynamicHull3d::from_device"));
  impl->insert(device_xyz, n, true);
  return DynamicHull3d(std::move(impl));
}

DynamicHull3d::DynamicHull3d(DynamicHull3d&&) noexcept = default;
DynamicHull3d& DynamicHull3d::operator=(DynamicHull3d&&) noexcept = default;
DynamicHull3d::~DynamicHull3d() = default;

void DynamicHull3d::insert(const double* xyz, std::int64_t n) {
  impl_->insert(xyz, n, false);
}
void DynamicHull3d::insert_device(const double* device_xyz, std::int64_t n) {
  impl_->insert(device_xyz, n, impl_->backend == Backend::Cuda);
}
void DynamicHull3d::move(const double* xyz, std::int64_t n) {
  impl_->move(xyz, n, false);
}
void DynamicHull3d::move_device(const double* device_xyz, std::int64_t n) {
  impl_->move(device_xyz, n, impl_->backend == Backend::Cuda);
}
void DynamicHull3d::remove(const std::int32_t* indices, std::int64_t count) {
  impl_->remove(indices, count, false);
}
void DynamicHull3d::remove_device(const std::int32_t* device_indices, std::int64_t count) {
  impl_->remove(device_indices, count, impl_->backend == Backend::Cuda);
}

std::int64_t DynamicHull3d::num_points() const {
  return impl_->kept->points();
}
std::int64_t DynamicHull3d::num_removed() const {
  return impl_->kept->removed();
}
std::int64_t DynamicHull3d::num_facets() const {
  return impl_->kept->simplices();
}
std::int64_t DynamicHull3d::num_vertices() const {
  return impl_->kept->vertices();
}
Backend DynamicHull3d::backend() const {
  return impl_->backend;
}
void DynamicHull3d::track_changes(bool on) {
  impl_->kept->track_changes(on);
}
SimplexChanges DynamicHull3d::changes() const {
  return impl_->changes("DynamicHull3d");
}
DeviceSimplexChanges DynamicHull3d::device_changes() const {
  return impl_->device_changes("DynamicHull3d");
}
const Stats& DynamicHull3d::stats() const {
  return impl_->stats;
}

ConvexHull3d DynamicHull3d::hull() const {
  ConvexHull3d r;
  impl_->kept->host_copy(r);
  return impl_->with_stats(std::move(r));
}

DeviceHull3d DynamicHull3d::device_hull() const {
  DeviceHull3d r;
  impl_->kept->device_copy(r);
  r.backend = impl_->backend;
  r.num_points = impl_->kept->points();
  return impl_->with_stats(std::move(r));
}

}  // namespace gpugeom
