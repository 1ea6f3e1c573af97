// Public entry of DynamicHull3d (issue 47): checks, the executor, the kept state's results.
#include <string>

#include "exec/dynamic_members.hpp"
#include "gpugeom/hull3d.hpp"
#include "hull3d/hull3d_backend.hpp"

namespace gpugeom {

namespace {
// (Method::Digital is taken: the updates find the same hull with the incremental method.)
void refuse_options(const Hull3dOptions& o) {
  const Hull3dBuffers& i = o.into;
  detail::refuse_dynamic_options(o, "DynamicHull3d", nullptr, "hull() or device_hull()",
                                 i.triangles, i.neighbors, i.vertices, i.equations);
}
}  // namespace

GG_DYNAMIC_MEMBERS(DynamicHull3d, hull3d, Hull3dOptions)

GG_DYNAMIC_RESULTS(DynamicHull3d, num_facets, num_vertices, vertices, ConvexHull3d, hull,
                   DeviceHull3d, device_hull)

}  // namespace gpugeom
