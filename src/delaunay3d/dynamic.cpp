// Public entry of DynamicDelaunay3d (issue 47): checks, the executor, the kept state's results.
#include <string>

#include "delaunay3d/del3d_backend.hpp"
#include "exec/dynamic_members.hpp"
#include "gpugeom/delaunay3d.hpp"

namespace gpugeom {

struct DynamicDelaunay3d::Impl : detail::DynamicImpl<del3d::Kept> {};

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

GG_DYNAMIC_MEMBERS(DynamicDelaunay3d, del3d, Delaunay3dOptions)

std::int64_t DynamicDelaunay3d::num_tetrahedra() const {
  return impl_->kept->simplices();
}
std::int64_t DynamicDelaunay3d::num_duplicates() const {
  return impl_->kept->duplicates();
}

Triangulation3d DynamicDelaunay3d::tetrahedralisation() const {
  Triangulation3d r;
  impl_->kept->host_copy(r);
  return impl_->with_stats(std::move(r));
}

DeviceTriangulation3d DynamicDelaunay3d::device_tetrahedralisation() const {
  DeviceTriangulation3d r;
  impl_->kept->device_copy(r);
  r.num_points = impl_->kept->points();
  r.backend = impl_->backend;
  return impl_->with_stats(std::move(r));
}

}  // namespace gpugeom
