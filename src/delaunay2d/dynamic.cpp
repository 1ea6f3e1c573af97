// Public entry of DynamicDelaunay2d (issue 47): checks, the executor, the kept state's results.
#include <string>

#include "delaunay2d/del2d_backend.hpp"
#include "exec/dynamic_members.hpp"
#include "gpugeom/delaunay2d.hpp"

namespace gpugeom {

struct DynamicDelaunay2d::Impl : detail::DynamicImpl<del2d::Kept> {};

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

GG_DYNAMIC_MEMBERS(DynamicDelaunay2d, del2d, Delaunay2dOptions)

std::int64_t DynamicDelaunay2d::num_triangles() const {
  return impl_->kept->simplices();
}
std::int64_t DynamicDelaunay2d::num_duplicates() const {
  return impl_->kept->duplicates();
}

Triangulation2d DynamicDelaunay2d::triangulation() const {
  Triangulation2d r;
  impl_->kept->host_copy(r);
  return impl_->with_stats(std::move(r));
}

DeviceTriangulation2d DynamicDelaunay2d::device_triangulation() const {
  DeviceTriangulation2d r;
  impl_->kept->device_copy(r);
  r.num_points = impl_->kept->points();
  r.backend = impl_->backend;
  return impl_->with_stats(std::move(r));
}

}  // namespace gpugeom
