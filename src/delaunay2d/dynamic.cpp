// Public entry of DynamicDelaunay2d (issue 47): checks, the executor, the kept state's results.
#include <string>

#include "delaunay2d/del2d_backend.hpp"
#include "exec/dynamic_members.hpp"
#include "gpugeom/delaunay2d.hpp"

namespace gpugeom {

namespace {
void refuse_options(const Delaunay2dOptions& o) {
  detail::refuse_dynamic_options(o, "DynamicDelaunay2d", "triangulation",
                                 "triangulation() or device_triangulation()", o.into.triangles,
                                 o.into.neighbors, o.into.duplicate_of);
}
}  // namespace

GG_DYNAMIC_MEMBERS(DynamicDelaunay2d, del2d, Delaunay2dOptions)

GG_DYNAMIC_RESULTS(DynamicDelaunay2d, num_triangles, num_duplicates, duplicates, Triangulation2d,
                   triangulation, DeviceTriangulation2d, device_triangulation)

}  // namespace gpugeom
