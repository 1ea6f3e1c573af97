// Public entry of DynamicHull3d (issue 47): checks, the executor, the kept state's results.
#include <string>

#include "exec/dynamic_members.hpp"
#include "gpugeom/hull3d.hpp"
#include "hull3d/hull3d_backend.hpp"

namespace gpugeom {

struct DynamicHull3d::Impl : detail::DynamicImpl<hull3d::Kept> {};

namespace {
void refuse_options(const Hull3dOptions& opt) {
  const Hull3dBuffers& i = opt.into;
  if (i.triangles || i.neighbors || i.vertices || i.equations)
    throw Error(ErrorCode::Unsupported,
                "DynamicHull3d: opt.into is not used; read the results with hull() or "
                "device_hull()");
}
}  // namespace

GG_DYNAMIC_MEMBERS(DynamicHull3d, hull3d, Hull3dOptions)

std::int64_t DynamicHull3d::num_facets() const {
  return impl_->kept->simplices();
}
std::int64_t DynamicHull3d::num_vertices() const {
  return impl_->kept->vertices();
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
