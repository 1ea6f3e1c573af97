// Public entry of DynamicDelaunay3d (issue 47): checks, the executor, the kept state's results.
#include <string>

#include "delaunay3d/del3d_backend.hpp"
#include "exec/dynamic_members.hpp"
#include "gpugeom/delaunay3d.hpp"

namespace gpugeom {

namespace {
void refuse_options(const Delaunay3dOptions& o) {
  const Triangulation3dBuffers& i = o.into;
  detail::refuse_dynamic_options(
      o, "DynamicDelaunay3d", "tetrahedra", "tetrahedralisation() or device_tetrahedralisation()",
      i.tetrahedra, i.neighbors, i.duplicate_of, i.vertex_to_simplex, i.hull_facets);
}
}  // namespace

GG_DYNAMIC_MEMBERS(DynamicDelaunay3d, del3d, Delaunay3dOptions)

GG_DYNAMIC_RESULTS(DynamicDelaunay3d, num_tetrahedra, num_duplicates, duplicates, Triangulation3d,
                   tetrahedralisation, DeviceTriangulation3d, device_tetrahedralisation)

}  // namespace gpugeom
